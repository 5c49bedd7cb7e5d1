//! Building: a binary BVH by binned SAH ([`binned`]) or, cutting triangles where the SAH says
//! so, with spatial splits ([`spatial`]); then collapsed into 8-wide nodes ([`collapse`]).

pub mod binned;
pub mod collapse;
pub mod spatial;
