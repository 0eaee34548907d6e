//! report.json and report.md: the same figures, for programs and for people.

use crate::obj::write_atomically;
use crate::scene_file::RunReport;
use std::path::{Path, PathBuf};

/// Writes `report.json` and `report.md` into `dir`.
pub fn write_report(dir: &Path, report: &RunReport) -> std::io::Result<Vec<PathBuf>> {
    let json = dir.join("report.json");
    write_atomically(&json, |out| {
        serde_json::to_writer_pretty(&mut *out, report).map_err(std::io::Error::other)?;
        writeln!(out)
    })?;
    let md = dir.join("report.md");
    write_atomically(&md, |out| {
        writeln!(
            out,
            "# {}\n",
            if report.scene.is_empty() {
                "cloth run"
            } else {
                &report.scene
            }
        )?;
        writeln!(
            out,
            "{} particles, {} triangles, {:.2} s in all.\n",
            report.particles, report.triangles, report.total_seconds
        )?;
        writeln!(
            out,
            "| stage | steps | seconds | CG iterations | ended |\n|---|---|---|---|---|"
        )?;
        for s in &report.stages {
            writeln!(
                out,
                "| {} | {} | {:.2} | {} | {} |",
                s.stage, s.steps, s.seconds, s.cg_iterations, s.ended
            )?;
        }
        writeln!(out, "\n| measure | value |\n|---|---|")?;
        writeln!(out, "| max warp strain | {:.3} % |", report.max_warp)?;
        writeln!(out, "| max weft strain | {:.3} % |", report.max_weft)?;
        writeln!(
            out,
            "| 99th percentile warp / weft | {:.3} % / {:.3} % |",
            report.p99_warp, report.p99_weft
        )?;
        writeln!(
            out,
            "| deepest penetration | {:.2e} m |",
            report.deepest_penetration
        )?;
        if let Some(gap) = report.largest_seam_gap {
            writeln!(out, "| largest seam gap at welding | {:.2} mm |", 1e3 * gap)?;
        }
        for w in &report.warnings {
            writeln!(out, "\nWarning: {w}")?;
        }
        Ok(())
    })?;
    Ok(vec![json, md])
}
