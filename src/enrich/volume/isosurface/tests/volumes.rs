//! Whole volumes: cells, ties, errors.
