-- Headless Neovim as an LSP client of `urdfcheck server` (issue 43): open the file given in URDFCHECK_NVIM_FILE,
-- wait for urdfcheck's diagnostics, write them as "CODE LINE" lines to URDFCHECK_NVIM_OUT, quit.
-- Run by tools/nvim_check.sh and tests/test_server.py; works with Neovim 0.7 (Debian's) and later.
local file = os.getenv("URDFCHECK_NVIM_FILE")
local out = os.getenv("URDFCHECK_NVIM_OUT")
local python = os.getenv("URDFCHECK_PYTHON") or "python3"
local root = vim.fn.fnamemodify(file, ":p:h")
while root ~= "/" and vim.fn.filereadable(root .. "/package.xml") == 0 do
  root = vim.fn.fnamemodify(root, ":h")
end
vim.cmd("edit " .. vim.fn.fnameescape(file))
local buf = vim.api.nvim_get_current_buf()
local id = vim.lsp.start_client({ cmd = { python, "-m", "urdfcheck", "server" }, root_dir = root, name = "urdfcheck" })
vim.lsp.buf_attach_client(buf, id)
local got = vim.wait(120000, function() return #vim.diagnostic.get(buf) > 0 end, 100)
local lines = {}
for _, d in ipairs(vim.diagnostic.get(buf)) do
  table.insert(lines, string.format("%s %d", d.code or "?", d.lnum + 1))
end
if not got then table.insert(lines, "TIMEOUT") end
vim.fn.writefile(lines, out)
vim.lsp.stop_client(id)
vim.cmd("qa!")
