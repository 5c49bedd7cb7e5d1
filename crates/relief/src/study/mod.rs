//! Studies: measurements of one feature of the relief renderer against its exact reference,
//! as library functions that return their rows (examples print them; the lab may record
//! them).
//!
//! - [`grazing`]: self-shadowing at grazing light against the exact hard shadow.

pub mod grazing;
