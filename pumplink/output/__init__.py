"""The output layer: it renders what the library computed (tables, JSON, CSV, batch files,
charts) and imports no kernel.  Degrees appear here, at the edge."""
