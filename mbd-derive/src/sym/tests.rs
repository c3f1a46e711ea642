//! Property tests of the symbolic engine.
