-- An include edited and not saved: opens the includer ($LWCPORT_FILES' first file) and the include
-- (its second), replaces line $LWCPORT_LINE of the include with the text of the file $LWCPORT_EDIT,
-- waits for the includer's diagnostics to change, undoes the edit and waits for them to change
-- again. To $LWCPORT_OUT: the includer's diagnostics at each step (one line each: the rule ids
-- with their lines) and whether the include was still modified after the edit.
package.path = vim.fn.fnamemodify(os.getenv('LWCPORT_SCRIPTS'), ':p') .. '?.lua;' .. package.path
local session = require('lsp_session')
local files = session.files()
local includer, include = session.open(files[1]), session.open(files[2])
session.wait_for_diagnostics(includer)

local function shown()
  local found = {}
  for _, d in ipairs(vim.diagnostic.get(includer)) do table.insert(found, d.code .. '@' .. (d.lnum + 1)) end
  table.sort(found)
  return table.concat(found, ' ')
end
local function wait_for_change(from, step)
  if not vim.wait(30000, function() return shown() ~= from end, 20) then
    session.fail('the includer\'s diagnostics did not change after ' .. step .. ': ' .. from)
  end
  return shown()
end

local before = shown()
local line = tonumber(os.getenv('LWCPORT_LINE'))
vim.api.nvim_buf_set_lines(include, line - 1, line, true, vim.fn.readfile(os.getenv('LWCPORT_EDIT')))
local edited = wait_for_change(before, 'the edit')
local modified = vim.bo[include].modified
vim.cmd('silent undo')
local undone = wait_for_change(edited, 'the undo')
session.report(table.concat({ before, edited, tostring(modified), undone }, '\n') .. '\n')
vim.cmd('qall!')
