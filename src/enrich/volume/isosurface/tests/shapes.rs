//! Whole volumes: known shapes.
