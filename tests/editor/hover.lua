-- Neovim's hover (vim.lsp.buf.hover) at the cursor: the text of the floating window it opens goes
-- to $LWCPORT_OUT.
package.path = vim.fn.fnamemodify(os.getenv('LWCPORT_SCRIPTS'), ':p') .. '?.lua;' .. package.path
local session = require('lsp_session')
session.start()
vim.lsp.buf.hover()
local text
local shown = vim.wait(30000, function()
  for _, win in ipairs(vim.api.nvim_list_wins()) do
    if vim.api.nvim_win_get_config(win).relative ~= '' then
      text = table.concat(vim.api.nvim_buf_get_lines(vim.api.nvim_win_get_buf(win), 0, -1, false), '\n')
      return true
    end
  end
  return false
end, 20)
if not shown then session.fail('no hover window opened') end
session.report(text)
vim.cmd('qall!')
