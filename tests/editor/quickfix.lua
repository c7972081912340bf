-- Neovim applies lwcport's preferred quick fix at the cursor through its own code-action path
-- (vim.lsp.buf.code_action; the choice a user makes in vim.ui.select is the preferred action),
-- then writes the buffer. The chosen action's title goes to $LWCPORT_OUT.
package.path = vim.fn.fnamemodify(os.getenv('LWCPORT_SCRIPTS'), ':p') .. '?.lua;' .. package.path
local session = require('lsp_session')
session.start()
local chosen
vim.ui.select = function(items, _, on_choice)
  for _, item in ipairs(items) do
    if item[2].isPreferred then
      chosen = item[2].title
      return on_choice(item)
    end
  end
  session.fail('no preferred quick fix among ' .. #items .. ' code actions')
end
vim.lsp.buf.code_action({ only = { 'quickfix' } })
if not vim.wait(30000, function() return vim.bo.modified end, 20) then session.fail('the quick fix changed nothing') end
vim.cmd('write')
session.report(chosen)
vim.cmd('qall!')
