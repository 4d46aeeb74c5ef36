//! # brdf-io
//!
//! Readers and writers for the measured formats, each producing
//! [`brdf_core::SampleSet`]s and, where the format is dense, an evaluable
//! measured BRDF.
