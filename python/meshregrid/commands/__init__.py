"""One module per CLI subcommand (see meshregrid.cli)."""
