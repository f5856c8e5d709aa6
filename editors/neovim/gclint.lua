-- gclint for Neovim 0.7 and later: G-code file types and the gclint language server.
-- Put it in your init.lua (or keep this file and add `dofile("/path/to/gclint.lua")` there).
vim.g.do_filetype_lua = 1 -- Neovim 0.7 only: read file types from Lua, as 0.8 and later always do
vim.filetype.add({
  extension = { gcode = "gcode", gco = "gcode", g = "gcode", nc = "gcode", ngc = "gcode", cnc = "gcode", tap = "gcode" },
})

local function gclint_root(path)
  -- the project folder: the nearest one up with a gclint.toml, .gclint.toml, pyproject.toml or .git
  local dir = vim.fn.fnamemodify(path, ":p:h")
  local root = dir
  for _, marker in ipairs({ "gclint.toml", ".gclint.toml", "pyproject.toml", ".git" }) do
    local found = vim.fn.findfile(marker, dir .. ";")
    if found == "" then found = vim.fn.finddir(marker, dir .. ";") end
    if found ~= "" then
      local parent = vim.fn.fnamemodify((vim.fn.fnamemodify(found, ":p"):gsub("/$", "")), ":h")
      if #parent > #root or root == dir then root = parent end
    end
  end
  return root
end

local gclint_clients = {} -- Neovim 0.7: one server per project folder
vim.api.nvim_create_autocmd("FileType", {
  pattern = "gcode",
  callback = function(args)
    local config = {
      name = "gclint",
      cmd = { "gclint", "server" }, -- or the full path, e.g. { "/home/me/gclint/.venv/bin/gclint", "server" }
      root_dir = gclint_root(vim.api.nvim_buf_get_name(args.buf)),
      init_options = { gclint = {} }, -- optional settings, e.g. { gclint = { printer = "30m" } }
    }
    if vim.lsp.start then -- Neovim 0.8 and later
      vim.lsp.start(config)
    else -- Neovim 0.7
      local id = gclint_clients[config.root_dir]
      if not id or not vim.lsp.get_client_by_id(id) then
        id = vim.lsp.start_client(config)
        gclint_clients[config.root_dir] = id
      end
      if id then vim.lsp.buf_attach_client(args.buf, id) end
    end
    -- the keys Neovim 0.11 maps by itself: K hover, gra code actions
    vim.keymap.set("n", "K", vim.lsp.buf.hover, { buffer = args.buf })
    vim.keymap.set({ "n", "v" }, "gra", vim.lsp.buf.code_action, { buffer = args.buf })
  end,
})
