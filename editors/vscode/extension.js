// gclint for VS Code: starts `gclint server` (the language server) for G-code files.
// The server does the work (diagnostics, hover, quick fixes); this file only launches it.
"use strict";

const { workspace, window } = require("vscode");
const { LanguageClient, TransportKind } = require("vscode-languageclient/node");

let client;

exports.activate = async function activate(context) {
  const command = workspace.getConfiguration("gclint").get("path") || "gclint";
  const serverOptions = { command, args: ["server"], transport: TransportKind.stdio };
  const clientOptions = {
    documentSelector: [
      { scheme: "file", language: "gcode" },
      { scheme: "untitled", language: "gcode" },
    ],
    // The server asks for the "gclint" section (workspace/configuration) and is told when it changes.
    synchronize: { configurationSection: "gclint" },
  };
  client = new LanguageClient("gclint", "gclint", serverOptions, clientOptions);
  try {
    await client.start();
  } catch (err) {
    window.showErrorMessage(
      `gclint: could not start "${command} server" (${err.message || err}). ` +
        "Install gclint (see docs/editors.md in gclint's sources), or set gclint.path to its full path."
    );
  }
};

exports.deactivate = function deactivate() {
  return client ? client.stop() : undefined;
};
