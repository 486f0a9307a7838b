"""`urdfcheck server`: a Language Server Protocol server over stdio (issue 43), a thin adapter over the lint
pipeline: `session` holds the documents and the answers, `lsp` speaks the protocol (pygls, imported lazily)."""
