// Keeps the library non-empty while the compositor is being written.
