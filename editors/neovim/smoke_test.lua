-- A headless check of a Neovim set-up for gclint: file types, the server started by the configuration,
-- diagnostics, hover, a code action applied, an edit checked again.  With the configuration of
-- docs/editors.md (editors/neovim/gclint.lua):
--
--   nvim --headless -u editors/neovim/gclint.lua -c "luafile editors/neovim/smoke_test.lua"
--
-- or with your own init.lua: nvim --headless -c "luafile /path/to/smoke_test.lua".  `gclint` must be on
-- PATH (or the configuration names its full path).  Works on Neovim 0.7 (Debian 12's) and later.
-- Prints what it sees and exits 0 when every step worked, 1 otherwise.
local out = function(...) io.stdout:write(table.concat({ ... }, " ") .. "\n") end
local failed = false
local function expect(ok, what)
  out((ok and "ok   " or "FAIL ") .. what)
  if not ok then failed = true end
end
local function finish() vim.cmd(failed and "cq" or "qa!") end

local dir = vim.fn.tempname()
vim.fn.mkdir(dir, "p")
vim.fn.writefile({ "[tool.gclint]" }, dir .. "/pyproject.toml") -- a project folder
local path = dir .. "/job.gcode"
vim.fn.writefile({
  "; gclint: dialect=hyrel",
  "M106 C255",
  "M109 T40 S215",
  "M106 T0 S127",
  "N1 G1 F600 X1*12",
  "M30",
}, path)

-- every G-code extension is the gcode file type (Neovim itself reads .g, .nc and .tap as other languages)
local types = {}
for _, ext in ipairs({ "gco", "g", "nc", "ngc", "cnc", "tap" }) do
  local other = dir .. "/other." .. ext
  vim.fn.writefile({ "G28" }, other)
  vim.cmd("edit " .. other)
  if vim.bo.filetype ~= "gcode" then table.insert(types, ext .. ": " .. vim.bo.filetype) end
end
expect(#types == 0, "file types (.gco .g .nc .ngc .cnc .tap are gcode)" .. (#types > 0 and ": " .. table.concat(types, ", ") or ""))

vim.cmd("edit " .. path)
local buf = vim.api.nvim_get_current_buf()
expect(vim.bo.filetype == "gcode", ".gcode is the gcode file type")
local client
vim.wait(15000, function()
  -- (vim.lsp.get_clients: Neovim 0.10 and later; buf_get_clients before)
  local attached = vim.lsp.get_clients and vim.lsp.get_clients({ bufnr = buf }) or vim.lsp.buf_get_clients(buf)
  for _, c in pairs(attached) do
    if c.name == "gclint" then client = c end
  end
  return client ~= nil
end, 50)
expect(client ~= nil, "the configuration started gclint server for the file")
if not client then finish() return end
expect(client.config.root_dir == dir or client.config.root_dir == vim.fn.resolve(dir), "root folder: the one with pyproject.toml")

local function codes()
  local seen = {}
  for _, d in ipairs(vim.diagnostic.get(buf)) do seen[d.code] = d end
  return seen
end
expect(vim.wait(15000, function() return codes()["HY003"] ~= nil and codes()["SX004"] ~= nil end, 50),
  "diagnostics (HY003 on line 3, SX004 on line 5)")
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
    if a.title:find("^SX004: set the checksum") then fix = a end
  end
end
expect(fix ~= nil, "a code action for the checksum (SX004: set the checksum to 48)")
if fix then
  vim.lsp.util.apply_workspace_edit(fix.edit, client.offset_encoding)
  expect(vim.api.nvim_buf_get_lines(buf, 4, 5, false)[1] == "N1 G1 F600 X1*48", "the code action applied")
end
vim.api.nvim_buf_set_text(buf, 2, 5, 2, 8, { "T0" }) -- T40 -> T0 by hand
expect(vim.wait(10000, function() return codes()["HY003"] == nil and codes()["SX004"] == nil end, 50),
  "edits checked again (HY003 and SX004 gone)")
vim.lsp.stop_client(client.id)
expect(vim.wait(5000, function() return vim.lsp.get_client_by_id(client.id) == nil end, 50), "server stopped")
finish()
