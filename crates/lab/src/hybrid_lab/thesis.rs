//! The thesis's frame-time tables 3.1–3.9 (1920×1080 on its GPU, one stage ray traced at a
//! time) as constants, and each of their cells beside our run's matching rows.
//!
//! Its Scene 1, 2 and 3 are our built-in `temple`, `courtyard` and `harbour` (sized as its
//! Table 2.1); its all-raster baselines are 10.9, 6.5 and 9.1 ms. A cell is compared as
//! `× baseline` (frame time over the same scene's baseline): our absolute times are on
//! another processor (a CPU), so only the ratios compare. Our ratio is the mean over the
//! scene's views of the matching row's `delta_ratio`.

use super::record::HybridRecord;
use crate::report::format_number;
use renderlab_hybrid::stages::shadows::SWEEP_SHADOW_SAMPLES;
use renderlab_hybrid::StageId;

/// The scenes of the thesis's columns (its Scene 1, 2, 3) by our built-in names.
pub const THESIS_SCENES: [&str; 3] = ["temple", "courtyard", "harbour"];

/// The thesis's all-raster frame time per scene, ms.
pub const THESIS_BASELINE_MS: [f64; 3] = [10.9, 6.5, 9.1];

/// The max roughness of the columns of tables 3.2–3.7.
pub const THESIS_ROUGHNESS: [f32; 4] = [0.01, 0.1, 0.5, 1.0];

/// The refraction rays of the rows of tables 3.2–3.4.
pub const THESIS_REFRACTION_RAYS: [u32; 6] = [3, 10, 20, 30, 40, 50];

/// The bounces of the rows of tables 3.5–3.7.
pub const THESIS_BOUNCES: [u32; 5] = [1, 2, 4, 8, 16];

/// The samples per pixel of the columns of Table 3.8 (GI).
pub const THESIS_GI_SPP: [u32; 4] = [4, 8, 16, 32];

/// The samples per pixel of the columns of Table 3.9 (AO).
pub const THESIS_AO_SPP: [u32; 4] = [1, 2, 4, 16];

/// Table 3.1: frame time with ray-traced shadows (all lights), per scene, ms.
pub const TABLE_3_1: [f64; 3] = [34.5, 18.1, 31.6];

/// Table 3.2: translucency, Scene 1; rows refraction rays, columns max roughness; ms.
pub const TABLE_3_2: [[f64; 4]; 6] = [
    [14.9, 15.3, 25.8, 26.2],
    [15.2, 15.4, 26.8, 27.2],
    [15.5, 15.8, 28.0, 28.2],
    [15.8, 16.1, 29.0, 29.2],
    [16.1, 16.3, 30.0, 30.2],
    [16.4, 16.7, 31.0, 31.2],
];

/// Table 3.3: translucency, Scene 2, ms.
pub const TABLE_3_3: [[f64; 4]; 6] = [
    [9.9, 10.0, 20.3, 20.3],
    [9.9, 10.4, 21.5, 22.3],
    [10.6, 10.7, 22.8, 23.0],
    [10.7, 10.8, 22.9, 23.0],
    [10.7, 10.8, 22.9, 23.0],
    [10.7, 10.8, 22.9, 23.0],
];

/// Table 3.4: translucency, Scene 3, ms.
pub const TABLE_3_4: [[f64; 4]; 6] = [
    [14.0, 14.2, 30.5, 31.6],
    [14.0, 14.2, 31.6, 32.6],
    [14.0, 14.4, 32.1, 33.4],
    [14.1, 14.7, 32.7, 33.5],
    [14.4, 14.9, 33.1, 33.7],
    [14.7, 15.0, 33.4, 34.5],
];

/// Table 3.5: reflections, Scene 1; rows max bounces, columns max roughness; ms.
pub const TABLE_3_5: [[f64; 4]; 5] = [
    [13.7, 14.2, 30.7, 34.1],
    [13.8, 14.9, 64.3, 84.7],
    [13.9, 15.4, 105.3, 232.0],
    [13.9, 15.6, 112.0, 285.0],
    [13.9, 15.6, 130.0, 295.0],
];

/// Table 3.6: reflections, Scene 2, ms.
pub const TABLE_3_6: [[f64; 4]; 5] = [
    [8.1, 8.7, 21.6, 22.0],
    [8.1, 8.8, 45.3, 51.8],
    [8.1, 8.8, 67.8, 134.0],
    [8.1, 8.8, 69.0, 168.0],
    [8.1, 8.9, 69.0, 168.0],
];

/// Table 3.7: reflections, Scene 3, ms.
pub const TABLE_3_7: [[f64; 4]; 5] = [
    [11.1, 11.6, 26.0, 29.5],
    [11.2, 11.9, 49.7, 74.3],
    [11.3, 12.0, 76.0, 211.0],
    [11.3, 12.1, 77.5, 248.0],
    [11.4, 12.4, 78.0, 251.0],
];

/// Table 3.8: global illumination; rows scenes, columns samples per pixel; ms.
pub const TABLE_3_8: [[f64; 4]; 3] =
    [[21.7, 23.1, 26.0, 31.9], [17.3, 18.4, 20.8, 25.6], [21.0, 22.6, 25.8, 32.2]];

/// Table 3.9: ambient occlusion; rows scenes, columns samples per pixel; ms.
pub const TABLE_3_9: [[f64; 4]; 3] =
    [[12.1, 12.9, 14.6, 18.4], [7.9, 9.4, 10.3, 13.2], [10.7, 11.3, 13.1, 16.7]];

/// One cell of a thesis table: which row of ours it matches and the thesis's frame time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// The thesis's scene (0, 1, 2 for its Scene 1, 2, 3).
    pub scene: usize,
    /// The stage ray traced.
    pub stage: StageId,
    /// The swept count the row has (`None`: any, as for shadows).
    pub count: Option<u32>,
    /// The swept max roughness (`None` for stages without one).
    pub roughness: Option<f32>,
    /// The thesis's frame time, ms.
    pub thesis_ms: f64,
}

impl Cell {
    /// The thesis's `× baseline`.
    pub fn thesis_ratio(&self) -> f64 {
        self.thesis_ms / THESIS_BASELINE_MS[self.scene]
    }

    /// Our mean `× baseline` over the matching rows of the scene's views (NaN without one).
    pub fn our_ratio(&self, records: &[HybridRecord]) -> f64 {
        let m: Vec<f64> = records.iter().filter(|r| self.matches(r)).map(|r| r.delta_ratio).collect();
        if m.is_empty() {
            f64::NAN
        } else {
            m.iter().sum::<f64>() / m.len() as f64
        }
    }

    /// Our mean GPU `× baseline` over the matching rows that ran on the GPU, each against its
    /// view's baseline's GPU frame time (NaN without one).
    pub fn our_gpu_ratio(&self, records: &[HybridRecord]) -> f64 {
        let m: Vec<f64> = records
            .iter()
            .filter(|r| self.matches(r))
            .filter_map(|r| {
                let base = records.iter().find(|b| b.is_baseline() && b.same_view(r))?;
                Some(r.gpu_frame_ms? / base.gpu_frame_ms?)
            })
            .collect();
        if m.is_empty() {
            f64::NAN
        } else {
            m.iter().sum::<f64>() / m.len() as f64
        }
    }

    /// Whether `r` is our row of this cell.
    pub fn matches(&self, r: &HybridRecord) -> bool {
        r.scene == THESIS_SCENES[self.scene]
            && r.stage_id() == Some(self.stage)
            && self.count.is_none_or(|c| r.count == Some(c))
            && match (self.roughness, r.max_roughness) {
                (None, _) => true,
                (Some(a), Some(b)) => (a - b).abs() <= 1e-6,
                (Some(_), None) => false,
            }
    }
}

/// One thesis table: its number, caption, headings and cells.
#[derive(Clone, Debug)]
pub struct ThesisTable {
    /// E.g. `3.2`.
    pub number: &'static str,
    /// What it measures.
    pub caption: String,
    /// The headings: the corner, then one per column.
    pub headers: Vec<String>,
    /// Each row's heading and cells.
    pub rows: Vec<(String, Vec<Cell>)>,
}

impl ThesisTable {
    /// The table's rows as the page prints them: per cell `thesis ms (×ratio) | ours ×ratio`,
    /// `–` for ours where the run has no such row, and `| GPU ×ratio` where rows ran on the
    /// GPU.
    pub fn beside_ours(&self, records: &[HybridRecord]) -> Vec<Vec<String>> {
        self.rows
            .iter()
            .map(|(head, cells)| {
                let mut row = vec![head.clone()];
                for c in cells {
                    let ours = c.our_ratio(records);
                    let ours =
                        if ours.is_nan() { "–".into() } else { format!("×{}", format_number(ours, 2)) };
                    let gpu = c.our_gpu_ratio(records);
                    let gpu = if gpu.is_nan() {
                        String::new()
                    } else {
                        format!(" | GPU ×{}", format_number(gpu, 2))
                    };
                    row.push(format!(
                        "{} ms (×{}) | {ours}{gpu}",
                        format_number(c.thesis_ms, 1),
                        format_number(c.thesis_ratio(), 2)
                    ));
                }
                row
            })
            .collect()
    }
}

fn scene_head(s: usize) -> String {
    format!("Scene {} ({})", s + 1, THESIS_SCENES[s])
}

/// A table with rows of `counts` and columns of max roughness, for scene `s`.
fn by_roughness<const R: usize>(
    number: &'static str,
    caption: &str,
    stage: StageId,
    s: usize,
    counts: &[u32; R],
    unit: &str,
    ms: &[[f64; 4]; R],
) -> ThesisTable {
    let mut headers = vec![format!("{unit} \\ max roughness")];
    headers.extend(THESIS_ROUGHNESS.iter().map(|r| format!("{r}")));
    ThesisTable {
        number,
        caption: format!("{caption}, {} (baseline {} ms)", scene_head(s), THESIS_BASELINE_MS[s]),
        headers,
        rows: (0..R)
            .map(|i| {
                let cells = (0..4)
                    .map(|j| Cell {
                        scene: s,
                        stage,
                        count: Some(counts[i]),
                        roughness: Some(THESIS_ROUGHNESS[j]),
                        thesis_ms: ms[i][j],
                    })
                    .collect();
                (counts[i].to_string(), cells)
            })
            .collect(),
    }
}

/// A table with rows of scenes and columns of samples per pixel.
fn by_spp(
    number: &'static str,
    caption: &str,
    stage: StageId,
    spp: &[u32; 4],
    ms: &[[f64; 4]; 3],
) -> ThesisTable {
    let mut headers = vec!["scene \\ samples per pixel".to_string()];
    headers.extend(spp.iter().map(|n| n.to_string()));
    ThesisTable {
        number,
        caption: caption.into(),
        headers,
        rows: (0..3)
            .map(|s| {
                let cells = (0..4)
                    .map(|j| Cell {
                        scene: s,
                        stage,
                        count: Some(spp[j]),
                        roughness: None,
                        thesis_ms: ms[s][j],
                    })
                    .collect();
                (scene_head(s), cells)
            })
            .collect(),
    }
}

/// Tables 3.1–3.9 in order.
pub fn thesis_tables() -> Vec<ThesisTable> {
    let mut out = vec![ThesisTable {
        number: "3.1",
        caption: "Ray-traced shadows (all lights)".into(),
        headers: vec![String::new(), scene_head(0), scene_head(1), scene_head(2)],
        rows: vec![(
            "frame".into(),
            (0..3)
                .map(|s| Cell {
                    scene: s,
                    stage: StageId::Shadows,
                    count: Some(SWEEP_SHADOW_SAMPLES),
                    roughness: None,
                    thesis_ms: TABLE_3_1[s],
                })
                .collect(),
        )],
    }];
    let translucency = [("3.2", &TABLE_3_2), ("3.3", &TABLE_3_3), ("3.4", &TABLE_3_4)];
    for (s, (n, t)) in translucency.into_iter().enumerate() {
        out.push(by_roughness(
            n,
            "Translucency",
            StageId::Translucency,
            s,
            &THESIS_REFRACTION_RAYS,
            "rays",
            t,
        ));
    }
    let reflections = [("3.5", &TABLE_3_5), ("3.6", &TABLE_3_6), ("3.7", &TABLE_3_7)];
    for (s, (n, t)) in reflections.into_iter().enumerate() {
        out.push(by_roughness(n, "Reflections", StageId::Reflections, s, &THESIS_BOUNCES, "bounces", t));
    }
    out.push(by_spp("3.8", "Global illumination", StageId::Gi, &THESIS_GI_SPP, &TABLE_3_8));
    out.push(by_spp("3.9", "Ambient occlusion", StageId::Ao, &THESIS_AO_SPP, &TABLE_3_9));
    out
}

/// The thesis's frame time and `× baseline` of our row `r`'s setting in its scene, if the
/// thesis tabulates it.
pub fn thesis_cell(r: &HybridRecord) -> Option<Cell> {
    thesis_tables().into_iter().flat_map(|t| t.rows).flat_map(|(_, cells)| cells).find(|c| c.matches(r))
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::record;
    use super::*;
    use renderlab_hybrid::stages;

    #[test]
    fn transcription_matches_the_thesis() {
        assert_eq!(TABLE_3_1, [34.5, 18.1, 31.6]);
        // The seed's ratios of Table 3.1: ×3.17, ×2.78, ×3.47.
        for (s, want) in [3.17, 2.78, 3.47].into_iter().enumerate() {
            assert!((TABLE_3_1[s] / THESIS_BASELINE_MS[s] - want).abs() < 0.005, "{s}");
        }
        assert_eq!(TABLE_3_2[0], [14.9, 15.3, 25.8, 26.2]);
        assert_eq!(TABLE_3_3[1][3], 22.3);
        assert_eq!(TABLE_3_4[3][0], 14.1);
        assert_eq!(TABLE_3_5[4][3], 295.0);
        assert_eq!(TABLE_3_5[2][2], 105.3);
        assert_eq!(TABLE_3_6[0][0], 8.1);
        assert_eq!(TABLE_3_7[4], [11.4, 12.4, 78.0, 251.0]);
        assert_eq!(TABLE_3_8[2], [21.0, 22.6, 25.8, 32.2]);
        assert_eq!(TABLE_3_9[1], [7.9, 9.4, 10.3, 13.2]);
        // Fig. 3.5's label: 295 − 10.9 = 284.1.
        assert!((TABLE_3_5[4][3] - THESIS_BASELINE_MS[0] - 284.1).abs() < 1e-9);
    }

    #[test]
    fn the_headings_are_our_sweeps_settings() {
        assert_eq!(THESIS_ROUGHNESS, stages::entry::THESIS_ROUGHNESS);
        assert_eq!(THESIS_REFRACTION_RAYS, stages::translucency::THESIS_REFRACTION_RAYS);
        assert_eq!(THESIS_BOUNCES, stages::reflections::THESIS_BOUNCES);
        assert_eq!(THESIS_GI_SPP, stages::gi::THESIS_GI_SPP);
        assert_eq!(THESIS_AO_SPP, stages::ao::THESIS_AO_SPP);
        let t = thesis_tables();
        assert_eq!(
            t.iter().map(|t| t.number).collect::<Vec<_>>(),
            ["3.1", "3.2", "3.3", "3.4", "3.5", "3.6", "3.7", "3.8", "3.9"]
        );
        let cells: usize = t.iter().flat_map(|t| &t.rows).map(|(_, c)| c.len()).sum();
        assert_eq!(cells, 3 + 3 * 24 + 3 * 20 + 12 + 12);
    }

    #[test]
    fn cells_match_our_rows_of_the_same_scene_and_setting() {
        let refl = Some(StageId::Reflections);
        let rows = [
            record("temple", refl, "rt-reflections b1 r0.01", (Some(1), Some(0.01)), 3.0, 20.0, vec![]),
            record("courtyard", refl, "rt-reflections b1 r0.01", (Some(1), Some(0.01)), 5.0, 20.0, vec![]),
            record("temple", Some(StageId::Shadows), "rt-shadows s1", (Some(1), None), 20.0, 20.0, vec![]),
        ];
        let t = thesis_tables();
        let t35 = t[4].beside_ours(&rows);
        assert_eq!(t35[0][0], "1");
        assert_eq!(t[4].headers[0], "bounces \\ max roughness");
        assert_eq!(t35[0][1], "13.7 ms (×1.26) | ×1.30");
        assert_eq!(t35[0][2], "14.2 ms (×1.30) | –");
        assert_eq!(
            t[0].beside_ours(&rows)[0][1..],
            ["34.5 ms (×3.17) | ×3.00", "18.1 ms (×2.78) | –", "31.6 ms (×3.47) | –"]
        );
        let c = thesis_cell(&rows[1]).unwrap();
        assert_eq!((c.scene, c.thesis_ms), (1, 8.1));
    }
}
