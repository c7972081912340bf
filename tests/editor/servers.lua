-- Opens each file of $LWCPORT_FILES and waits for lwcport's diagnostics on it; to $LWCPORT_OUT,
-- one line a file (its name, the id of the client that serves it, the process id of that
-- client's server), then how many clients Neovim runs and how many lwcport processes it started.
package.path = vim.fn.fnamemodify(os.getenv('LWCPORT_SCRIPTS'), ':p') .. '?.lua;' .. package.path
local session = require('lsp_session')
local lines = {}
for _, buf in ipairs(session.open_all()) do
  local client = session.client(buf)
  table.insert(lines, table.concat({ vim.fn.fnamemodify(vim.api.nvim_buf_get_name(buf), ':t'), client.id, client.rpc.pid }, ' '))
end
table.insert(lines, 'clients ' .. #vim.lsp.get_active_clients())
-- Neovim's children named lwcport, from /proc/<pid>/stat: "pid (name) state parent-pid ...".
local processes = 0
for _, stat in ipairs(vim.fn.glob('/proc/[0-9]*/stat', false, true)) do
  local file = io.open(stat)
  if file then
    local name, parent = file:read('*a'):match('^%d+ %((.*)%) %S+ (%d+)')
    file:close()
    if name == 'lwcport' and tonumber(parent) == vim.fn.getpid() then processes = processes + 1 end
  end
end
table.insert(lines, 'processes ' .. processes)
session.report(table.concat(lines, '\n') .. '\n')
vim.cmd('qall!')
