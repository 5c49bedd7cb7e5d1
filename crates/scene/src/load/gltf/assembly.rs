//! Primitive assembly: the triangles a glTF primitive draws from its vertex sequence in
//! each draw mode (lists, strips, fans), and how many it draws before they are read.

use ::gltf::mesh::Mode;

/// How many triangles [`assemble`] makes of `n` vertices drawn in `mode`.
pub(super) fn assembled_count(mode: Mode, n: usize) -> usize {
    match mode {
        Mode::TriangleStrip | Mode::TriangleFan => n.saturating_sub(2),
        _ => n / 3,
    }
}

/// The triangles a primitive of `mode` draws from its vertex sequence `idx`, as the glTF
/// specification (§3.7.2.1) assembles them: lists by threes (a trailing partial triangle
/// dropped), strips with every other triangle's first two vertices swapped so that all keep
/// the first one's winding, fans around the first vertex.
pub(super) fn assemble(mode: Mode, idx: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => {
            (0..idx.len().saturating_sub(2))
                .map(|i| {
                    if i % 2 == 0 {
                        [idx[i], idx[i + 1], idx[i + 2]]
                    } else {
                        [idx[i + 1], idx[i], idx[i + 2]]
                    }
                })
                .collect()
        }
        Mode::TriangleFan => (1..idx.len().saturating_sub(1)).map(|i| [idx[i], idx[i + 1], idx[0]]).collect(),
        _ => idx.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::{assemble, Mode};

    #[test]
    fn strips_keep_the_winding_and_fans_turn_around_the_first_vertex() {
        let idx = [10, 11, 12, 13, 14];
        assert_eq!(assemble(Mode::TriangleStrip, &idx), vec![[10, 11, 12], [12, 11, 13], [12, 13, 14]]);
        assert_eq!(assemble(Mode::TriangleFan, &idx), vec![[11, 12, 10], [12, 13, 10], [13, 14, 10]]);
        assert_eq!(assemble(Mode::Triangles, &idx), vec![[10, 11, 12]]);
        for mode in [Mode::TriangleStrip, Mode::TriangleFan, Mode::Triangles] {
            assert!(assemble(mode, &idx[..2]).is_empty());
            assert!(assemble(mode, &[]).is_empty());
        }
    }
}
