-- A headless check that Neovim and `gclint server` talk: diagnostics, hover, a quick fix, an edit.
--
--   GCLINT_CMD=/path/to/venv/bin/gclint nvim --headless -u NONE -c "luafile editors/neovim/smoke_test.lua"
--
-- Works on Neovim 0.7 and later (it uses vim.lsp.start_client, which every version has).  Prints what
-- it sees and exits 0 when every step worked, 1 otherwise.
local out = function(...) io.stdout:write(table.concat({ ... }, " ") .. "\n") end
local failed = false
local function expect(ok, what)
  out((ok and "ok   " or "FAIL ") .. what)
  if not ok then failed = true end
end

local dir = vim.fn.tempname()
vim.fn.mkdir(dir, "p")
local path = dir .. "/job.gcode"
vim.fn.writefile({
  "; gclint: dialect=hyrel",
  "M106 C255",
  "M109 T40 S215",
  "M106 T0 S127",
  "N1 G1 F600 X1*12",
  "M30",
}, path)
vim.cmd("edit " .. path)
local buf = vim.api.nvim_get_current_buf()
local id = vim.lsp.start_client({
  name = "gclint",
  cmd = { os.getenv("GCLINT_CMD") or "gclint", "server" },
  root_dir = dir,
})
expect(id ~= nil, "server started")
vim.lsp.buf_attach_client(buf, id)
local function codes()
  local seen = {}
  for _, d in ipairs(vim.diagnostic.get(buf)) do seen[d.code] = d end
  return seen
end
expect(vim.wait(15000, function() return codes()["HY003"] ~= nil end, 50), "diagnostics (HY003 on line 3)")
for _, d in ipairs(vim.diagnostic.get(buf)) do
  out(string.format("       %d:%d-%d %s %s", d.lnum + 1, d.col, d.end_col, d.code or "?", d.message:sub(1, 60)))
end
local uri = vim.uri_from_bufnr(buf)
local res = vim.lsp.buf_request_sync(buf, "textDocument/hover",
  { textDocument = { uri = uri }, position = { line = 3, character = 9 } }, 10000) or {}
local hover
for _, r in pairs(res) do if r.result then hover = r.result.contents.value end end
expect(hover ~= nil and hover:find("49.8", 1, true) ~= nil, "hover on M106 T0 S127 (49.8 % of the C255 range)")
if hover then out(hover) end

res = vim.lsp.buf_request_sync(buf, "textDocument/codeAction", {
  textDocument = { uri = uri },
  range = { start = { line = 4, character = 0 }, ["end"] = { line = 4, character = 0 } },
  context = { diagnostics = {} },
}, 10000) or {}
local fix
for _, r in pairs(res) do
  for _, a in ipairs(r.result or {}) do
    out("       action: " .. a.title)
    if a.isPreferred then fix = a end
  end
end
expect(fix ~= nil, "a quick fix for the checksum")
if fix then
  vim.lsp.util.apply_workspace_edit(fix.edit, vim.lsp.get_client_by_id(id).offset_encoding)
  expect(vim.api.nvim_buf_get_lines(buf, 4, 5, false)[1] == "N1 G1 F600 X1*48", "fix applied")
end
vim.api.nvim_buf_set_text(buf, 2, 5, 2, 8, { "T0" })  -- T40 -> T0 by hand
expect(vim.wait(5000, function() return codes()["HY003"] == nil and codes()["SX004"] == nil end, 50),
  "edits re-checked (HY003 and SX004 gone)")
vim.lsp.stop_client(id)
expect(vim.wait(5000, function() return vim.lsp.get_client_by_id(id) == nil end, 50), "server stopped")
vim.cmd(failed and "cq" or "qa!")
