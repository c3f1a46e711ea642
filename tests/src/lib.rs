//! Integration tests of the mbd facade live in `tests/`.
