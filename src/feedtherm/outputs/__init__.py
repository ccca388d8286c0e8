"""Files and console views of results; they only read results, never solver internals."""
