-- Shared by the Neovim scripts. Neovim runs with the set-up docs/editors.md shows as its init.lua
-- (tests/cli/editor_test.cpp takes it from the page), so the scripts only open files as a user
-- does: the set-up gives them their file type and lwcport's server. Any failure ends Neovim with
-- exit code 1 and a reason.
local M = {}

function M.fail(reason)
  io.stderr:write('neovim: ' .. reason .. '\n')
  vim.cmd('cquit 1')
end

-- The files in $LWCPORT_FILES (separated by white space).
function M.files()
  return vim.split(os.getenv('LWCPORT_FILES'), '%s+', { trimempty = true })
end

-- Opens `file` in the current window (the buffer it shows stays loaded when another is opened);
-- its buffer number.
function M.open(file)
  vim.o.hidden = true
  vim.cmd('edit ' .. vim.fn.fnameescape(file))
  return vim.api.nvim_get_current_buf()
end

-- The client named lwcport that serves buffer `buf`, or nil.
function M.client(buf)
  for _, client in pairs(vim.lsp.buf_get_clients(buf)) do
    if client.name == 'lwcport' then return client end
  end
end

-- Waits until lwcport serves buffer `buf` and has published diagnostics for it, or fails.
function M.wait_for_diagnostics(buf)
  local served = vim.wait(30000, function() return M.client(buf) ~= nil and #vim.diagnostic.get(buf) > 0 end, 20)
  if not served then
    M.fail(vim.api.nvim_buf_get_name(buf) .. ' (file type "' .. vim.bo[buf].filetype .. '"): ' ..
           (M.client(buf) and 'no diagnostics arrived' or 'no lwcport server serves it'))
  end
end

-- Opens every file of $LWCPORT_FILES, then waits for lwcport's diagnostics on each; their buffers.
function M.open_all()
  local buffers = {}
  for _, file in ipairs(M.files()) do table.insert(buffers, M.open(file)) end
  for _, buf in ipairs(buffers) do M.wait_for_diagnostics(buf) end
  return buffers
end

-- Opens $LWCPORT_FILE, waits for its diagnostics and puts the cursor at $LWCPORT_LINE (1-based)
-- and $LWCPORT_COLUMN (0-based byte).
function M.start()
  local buf = M.open(os.getenv('LWCPORT_FILE'))
  M.wait_for_diagnostics(buf)
  vim.api.nvim_win_set_cursor(0, { tonumber(os.getenv('LWCPORT_LINE')), tonumber(os.getenv('LWCPORT_COLUMN')) })
end

-- Writes `text` to $LWCPORT_OUT.
function M.report(text)
  local out = io.open(os.getenv('LWCPORT_OUT'), 'w')
  out:write(text)
  out:close()
end

return M
