//! The results of a run directory, made from its persisted rows alone: `results.json`,
//! `results.csv` and `index.html`. A finished run, a resumed one and a merge of shards call
//! the same function on the same rows, so they give the same results.

use super::claims::claims;
use super::page::write_page;
use super::pareto::StageFront;
use super::record::RefInfo;
use super::record::{by_view, HybridRecord, RowResult, ERROR_SPACE};
use super::store::{read_json, Manifest, RunDir, View};
use super::sweep::Stage;
use crate::error::{LabError, Result};
use crate::report::format_number;
use crate::results::{write_csv, write_json};
use renderlab_hybrid::TermScore;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// What an assembled run hands back.
#[derive(Clone, Debug)]
pub struct HybridSummary {
    /// The run's manifest (settings and shard).
    pub manifest: Manifest,
    /// One record per finished row, in the run's canonical order.
    pub records: Vec<HybridRecord>,
    /// Rows of this directory's shard not finished (0 for a complete run).
    pub missing: usize,
    /// Human-readable conclusions.
    pub findings: Vec<String>,
    /// One sentence for an index page.
    pub headline: String,
    /// The HTML page.
    pub index: PathBuf,
    /// The first view's reference image, if written.
    pub headline_image: Option<PathBuf>,
    /// What the run found damaged in the directory it resumed and repaired (one line each;
    /// empty for a fresh run and a merge).
    pub repairs: Vec<String>,
}

/// A view's reference as `results.json` lists it.
#[derive(Clone, Debug, Serialize)]
pub struct ReferenceEntry<'a> {
    /// The view.
    #[serde(flatten)]
    pub view: &'a View,
    /// Its reference.
    #[serde(flatten)]
    pub info: &'a RefInfo,
}

/// A record as `results.json` lists it: its flat fields (the CSV's columns), then every
/// term's score and the direct term's over the area-lit pixels.
#[derive(Clone, Debug, Serialize)]
pub struct RecordEntry<'a> {
    /// The record.
    #[serde(flatten)]
    pub record: &'a HybridRecord,
    /// Every term's score, in the order of `Term::ALL`.
    pub term_scores: &'a [TermScore],
    /// The direct term over the pixels the area lights light most.
    pub direct_area_lit: Option<&'a TermScore>,
}

/// `results.json`.
#[derive(Serialize)]
struct Results<'a> {
    manifest: &'a Manifest,
    /// How errors are measured.
    error_space: &'static str,
    references: Vec<ReferenceEntry<'a>>,
    records: Vec<RecordEntry<'a>>,
}

/// Reads every finished row of `out`'s shard, writes `results.json`, `results.csv` and
/// `index.html`, and summarises.
pub fn assemble(out: &Path) -> Result<HybridSummary> {
    let dir = RunDir::new(out);
    let manifest = dir
        .manifest()?
        .ok_or_else(|| LabError::Hybrid(format!("{}: no run.json: not a hybrid run", out.display())))?;
    let s = &manifest.settings;
    let all = s.rows();
    let mut rows: Vec<(RowResult, &View)> = Vec::new();
    let mut missing = 0;
    for (i, (id, view, row)) in all.iter().enumerate() {
        if !manifest.shard.owns(i) {
            continue;
        }
        match dir.row(id, view, row, s.run.write_images)? {
            Some(r) => rows.push((r, view)),
            None => missing += 1,
        }
    }
    let mut refs: Vec<(&View, RefInfo)> = Vec::new();
    for v in &s.views {
        let p = dir.ref_json(v);
        if p.is_file() {
            refs.push((v, read_json(&p)?));
        }
    }
    let mut records = Vec::with_capacity(rows.len());
    for (r, view) in &rows {
        let info = refs.iter().find(|(v, _)| v == view).map(|(_, i)| i);
        let info = info.ok_or_else(|| {
            LabError::Hybrid(format!("{}: row {} has no reference in refs/", out.display(), r.id))
        })?;
        let baseline = rows.iter().find(|(b, v)| v == view && b.row.stage == Stage::Baseline).map(|(b, _)| b);
        records.push(HybridRecord::new(r, view.camera_index, baseline, s.run.width, s.run.height, info));
    }
    let rows: Vec<RowResult> = rows.into_iter().map(|(r, _)| r).collect();
    let results = Results {
        manifest: &manifest,
        error_space: ERROR_SPACE,
        references: refs.iter().map(|(view, info)| ReferenceEntry { view, info }).collect(),
        records: records
            .iter()
            .map(|record| RecordEntry {
                record,
                term_scores: &record.terms,
                direct_area_lit: record.direct_area_lit.as_ref(),
            })
            .collect(),
    };
    write_json(out.join("results.json"), &results)?;
    write_csv(out.join("results.csv"), &records)?;
    let findings = findings(&records);
    let headline = headline(&records, &manifest);
    let index = out.join("index.html");
    write_page(&index, &manifest, &refs, &rows, &records, &findings, missing)?;
    let headline_image = refs.first().map(|(_, i)| out.join(&i.image)).filter(|p| p.is_file());
    Ok(HybridSummary {
        manifest,
        records,
        missing,
        findings,
        headline,
        index,
        headline_image,
        repairs: Vec::new(),
    })
}

/// Per stage: its cost and best whole-frame error over every view, then on each view its
/// Pareto front on its own term; then each claim of the thesis with its verdict.
fn findings(records: &[HybridRecord]) -> Vec<String> {
    let mut out = Vec::new();
    let views = by_view(records);
    for stage in Stage::swept() {
        let rs: Vec<&HybridRecord> = records.iter().filter(|r| r.stage == stage.name()).collect();
        if rs.is_empty() {
            continue;
        }
        let mean = |f: &dyn Fn(&HybridRecord) -> f64| rs.iter().map(|r| f(r)).sum::<f64>() / rs.len() as f64;
        let best = rs.iter().copied().max_by(|a, b| a.psnr_db.total_cmp(&b.psnr_db)).expect("non-empty");
        let floor = rs.iter().filter(|r| r.at_noise_floor).count();
        let mut line = format!(
            "Ray-traced {}: {} rows, frame time {}× the baseline on average (mean delta {} ms); best whole-frame PSNR {} dB ({}, {} {}){}.",
            stage.name(),
            rs.len(),
            format_number(mean(&|r| r.delta_ratio), 2),
            format_number(mean(&|r| r.delta_ms), 1),
            format_number(best.psnr_db, 2),
            best.label,
            best.scene,
            best.camera,
            if floor > 0 { format!("; {floor} rows reach the reference's noise floor (no lower error claimed)") } else { String::new() },
        );
        if let Stage::Swept(id) = stage {
            for v in &views {
                if let Some(f) = StageFront::of(v, id) {
                    line += &format!(" {}: {}", v[0].view_title(), f.sentence());
                }
            }
        }
        out.push(line);
    }
    out.extend(claims(records).iter().map(|c| c.finding()));
    out
}

/// One sentence: rows, views, the baseline's error and the claims' verdicts.
fn headline(records: &[HybridRecord], m: &Manifest) -> String {
    let base: Vec<&HybridRecord> = records.iter().filter(|r| r.is_baseline()).collect();
    let psnr = if base.is_empty() {
        "–".into()
    } else {
        format_number(base.iter().map(|r| r.psnr_db).sum::<f64>() / base.len() as f64, 2)
    };
    let verdicts: Vec<String> =
        claims(records).iter().map(|c| format!("({}) {}", c.id, c.overall())).collect();
    format!(
        "{} rows over {} views at {}×{} against {}-spp path-traced references; the all-raster baseline's mean PSNR is {psnr} dB; the thesis's claims: {}.",
        records.len(),
        m.settings.views.len(),
        m.settings.run.width,
        m.settings.run.height,
        m.settings.run.reference_spp,
        verdicts.join(", "),
    )
}
