//! Building: a binary BVH by binned SAH ([`binned`]), then collapsed into 8-wide nodes
//! ([`collapse`]).

pub mod binned;
pub mod collapse;
