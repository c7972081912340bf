-- Shared by the Neovim scripts: start lwcport's server for the file in $LWCPORT_FILE through
-- Neovim's built-in client, wait for its diagnostics and put the cursor at $LWCPORT_LINE (1-based)
-- and $LWCPORT_COLUMN (0-based byte). Any failure ends Neovim with exit code 1 and a reason.
local M = {}

function M.fail(reason)
  io.stderr:write('neovim: ' .. reason .. '\n')
  vim.cmd('cquit 1')
end

function M.start()
  local file = os.getenv('LWCPORT_FILE')
  vim.cmd('edit ' .. vim.fn.fnameescape(file))
  local client = vim.lsp.start_client({
    name = 'lwcport',
    cmd = { os.getenv('LWCPORT_BIN'), 'lsp' },
    root_dir = vim.fn.fnamemodify(file, ':p:h'),
  })
  if not client then M.fail('the language server did not start') end
  vim.lsp.buf_attach_client(0, client)
  if not vim.wait(30000, function() return #vim.diagnostic.get(0) > 0 end, 20) then M.fail('no diagnostics arrived') end
  vim.api.nvim_win_set_cursor(0, { tonumber(os.getenv('LWCPORT_LINE')), tonumber(os.getenv('LWCPORT_COLUMN')) })
end

-- Writes `text` to $LWCPORT_OUT.
function M.report(text)
  local out = io.open(os.getenv('LWCPORT_OUT'), 'w')
  out:write(text)
  out:close()
end

return M
