-- Opens each file of $LWCPORT_FILES and waits for lwcport's diagnostics on it; one line a file
-- to $LWCPORT_OUT: its name, its file type, the name of the server that serves it and how many
-- diagnostics it has.
package.path = vim.fn.fnamemodify(os.getenv('LWCPORT_SCRIPTS'), ':p') .. '?.lua;' .. package.path
local session = require('lsp_session')
local lines = {}
for _, buf in ipairs(session.open_all()) do
  table.insert(lines, table.concat({ vim.fn.fnamemodify(vim.api.nvim_buf_get_name(buf), ':t'), vim.bo[buf].filetype,
                                     session.client(buf).name, #vim.diagnostic.get(buf) }, ' '))
end
session.report(table.concat(lines, '\n') .. '\n')
vim.cmd('qall!')
