//! report.json and report.md: the same figures, for programs and for people.

use crate::scene_file::{RunOutcome, RunReport};
use cloth_formats::atomic::write_atomically;
use cloth_garment::garment::closing_said;
use cloth_garment::sewing::{SeamStall, StallThen};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `report.json` and `report.md` into `dir`.
/// `plots` are pictures already in `dir`, each a file name and what it shows, which
/// `report.md` shows in a section of their own.
pub fn write_report(dir: &Path, report: &RunReport, plots: &[(&str, &str)]) -> std::io::Result<Vec<PathBuf>> {
    let json = dir.join("report.json");
    write_atomically(&json, |out| {
        serde_json::to_writer_pretty(&mut *out, report).map_err(std::io::Error::other)?;
        writeln!(out)
    })?;
    let md = dir.join("report.md");
    write_atomically(&md, |out| {
        write_markdown(out, report)?;
        if !plots.is_empty() {
            writeln!(out, "\n## Plots")?;
        }
        for (file, caption) in plots {
            writeln!(out, "\n{caption}\n\n![{caption}]({file})")?;
        }
        Ok(())
    })?;
    Ok(vec![json, md])
}

fn write_markdown(out: &mut dyn Write, report: &RunReport) -> std::io::Result<()> {
    let title = if report.scene.is_empty() {
        "cloth run"
    } else {
        &report.scene
    };
    writeln!(out, "# {title}\n")?;
    match &report.outcome {
        RunOutcome::Finished => {}
        RunOutcome::Interrupted { stage, step } => writeln!(
            out,
            "**Interrupted** at {stage} step {step}: the outputs hold the state reached.\n"
        )?,
        RunOutcome::Failed { stage, step, error } => writeln!(
            out,
            "**Failed**: {error}. The outputs hold the last good state, after {stage} step {step}.\n"
        )?,
    }
    writeln!(
        out,
        "{} particles, {} triangles, {:.2} s in all (cloth {}).\n",
        report.particles, report.triangles, report.total_seconds, report.engine_version
    )?;
    writeln!(
        out,
        "| stage | steps | seconds | CG iterations | steps cut (retries) | ended |\n|---|---|---|---|---|---|"
    )?;
    for s in &report.stages {
        writeln!(
            out,
            "| {} | {} | {:.2} | {} | {} ({}) | {} |",
            s.stage, s.steps, s.seconds, s.cg_iterations, s.steps_cut, s.retries, s.ended
        )?;
    }
    let s = &report.strain;
    writeln!(out, "\n| measure | value |\n|---|---|")?;
    writeln!(out, "| max warp strain | {:.3} % |", s.max_warp)?;
    writeln!(out, "| max weft strain | {:.3} % |", s.max_weft)?;
    writeln!(
        out,
        "| 99th percentile warp / weft | {:.3} % / {:.3} % |",
        s.p99_warp, s.p99_weft
    )?;
    writeln!(
        out,
        "| deepest penetration | {:.2e} m |",
        report.deepest_penetration
    )?;
    writeln!(
        out,
        "| intersecting edge-triangle pairs, cloth / cloth and bodies | {} / {} |",
        report.self_intersections, report.body_intersections
    )?;
    if report.thin_parts_passed > 0 {
        writeln!(
            out,
            "| crossings of the body's thin parts by panels passing them (skirts through the hands) | {} |",
            report.thin_parts_passed
        )?;
    }
    if let Some(gap) = report.largest_seam_gap {
        writeln!(out, "| largest seam gap | {:.2} mm |", 1e3 * gap)?;
    }
    if let Some(c) = report.weld_crossings.filter(|c| c.found > 0) {
        writeln!(
            out,
            "| crossings the weld made (cloth caught between a seam's sides), found / left after moving it out | {} / {} |",
            c.found, c.left
        )?;
    }
    if let Some(u) = &report.untangling_at_rest {
        for (k, smoothed) in u.smoothed.iter().enumerate() {
            let s = smoothed.smoothing;
            let on = match smoothed.draped_on {
                Some(d) => format!(
                    "{} ({} through the body) in {} steps draped on, {} kept",
                    d.after,
                    d.body_after,
                    d.steps,
                    if d.kept { "that" } else { "the rest before" }
                ),
                None => "not draped on".to_string(),
            };
            let again = if k == 0 { "" } else { " again" };
            writeln!(
                out,
                "| at rest through itself, smoothed apart{again} where it crossed: crossings first / after smoothing ({} rounds, {:.1} mm at most) / at rest after | {} / {} / {on} |",
                s.rounds,
                1e3 * s.most_moved,
                s.before,
                s.left
            )?;
        }
        if let Some(d) = u.loose {
            let kept = if d.kept { "this one" } else { "the one before" };
            writeln!(
                out,
                "| still through itself, draped again from sewn, loose where it crossed: crossings at rest, its steps | {} ({} through the body) in {} steps, {kept} kept |",
                d.after, d.body_after, d.steps
            )?;
        }
    }
    if let Some(n) = report.attached_particles.filter(|&n| n > 0) {
        writeln!(
            out,
            "| particles of attached edges (a waist, a neckline), each held on one side of where it was placed | {n} |"
        )?;
    }
    if let Some(n) = report.pinned_particles.filter(|&n| n > 0) {
        writeln!(
            out,
            "| vertices of pinned edges and panels, held where the sewing left them for the whole drape | {n} |"
        )?;
    }
    if let Some(fit) = &report.fit {
        writeln!(
            out,
            "| where most stretched ({} in '{}'), the cloth round the body at rest / worn, and the body's girth inside it | {:.1} cm / {:.1} cm, {:.1} cm: {} |",
            fit.thread,
            fit.panel,
            100.0 * fit.cloth_at_rest,
            100.0 * fit.cloth_worn,
            100.0 * fit.body_girth,
            fit.asks_said()
        )?;
    }
    if let Some(verdict) = &report.verdict {
        writeln!(out, "\n**Verdict**: {verdict}.")?;
    }
    write_panels(out, report)?;
    if !report.seam_stalls.is_empty() {
        writeln!(
            out,
            "\nSeams that stopped closing while sewn, and how they were closed:\n\n\
             | step | widest seam | gap, mm | then |\n|---|---|---|---|"
        )?;
        for s in &report.seam_stalls {
            let then = then_said(s);
            writeln!(out, "| {} | {} | {:.2} | {then} |", s.step, s.seam, 1e3 * s.gap)?;
        }
    }
    if !report.caught_layers.is_empty() {
        writeln!(
            out,
            "\nLayers of cloth found across a seam's sides while sewn, and the panel let through each:\n\n\
             | step | seam | layer | let through it | pairs across | through after step |\n|---|---|---|---|---|---|"
        )?;
        for c in &report.caught_layers {
            let passed = c
                .passed
                .map_or_else(|| "not by the weld".to_string(), |s| s.to_string());
            writeln!(
                out,
                "| {} | {} | {} | {} | {} | {passed} |",
                c.step, c.seam, c.layer, c.passing, c.pairs
            )?;
        }
    }
    if !report.tangles.is_empty() {
        writeln!(
            out,
            "\nPieces found through each other when a stage began, let pass each other until apart:\n\n\
             | stage | pieces | crossing edges | apart after step |\n|---|---|---|---|"
        )?;
        for t in &report.tangles {
            let apart = t.apart_after.map_or("not apart".to_string(), |s| s.to_string());
            writeln!(
                out,
                "| {} | {} and {} | {} | {} |",
                t.stage, t.pieces[0], t.pieces[1], t.crossings, apart
            )?;
        }
    }
    if !report.checkpoints.is_empty() {
        writeln!(
            out,
            "\nLargest stretch after N steps (iterations):\n\n\
             | stage | steps | time, s | max warp | max weft | ms per step (median) |\n\
             |---|---|---|---|---|---|"
        )?;
        for c in &report.checkpoints {
            writeln!(
                out,
                "| {} | {} | {:.4} | {:.3} % | {:.3} % | {:.2} |",
                c.stage, c.step, c.time, c.max_warp, c.max_weft, c.median_step_ms
            )?;
        }
    }
    if let Some(last) = report.frames.last() {
        writeln!(
            out,
            "\n{} frames in `{}` (the last at {} step {}); the most intersecting edge-triangle \
             pairs of the cloth in one: {}.",
            report.frames.len(),
            Path::new(&last.file)
                .parent()
                .map_or("".into(), |p| p.display().to_string()),
            last.stage,
            last.step,
            report
                .frames
                .iter()
                .map(|f| f.self_intersections)
                .max()
                .unwrap_or(0)
        )?;
    }
    for w in &report.warnings {
        writeln!(out, "\nWarning: {w}")?;
    }
    Ok(())
}

/// The table of strain and intersections by panel, most stretched first.
fn write_panels(out: &mut dyn Write, report: &RunReport) -> std::io::Result<()> {
    if report.panels.is_empty() {
        return Ok(());
    }
    writeln!(
        out,
        "\nBy panel, the most stretched first:\n\n\
         | panel | triangles | p99 warp / weft, % | max warp / weft, % | through the cloth | through the body |\n\
         |---|---|---|---|---|---|"
    )?;
    let mut panels: Vec<_> = report.panels.iter().collect();
    panels.sort_by(|a, b| b.strain.p99().0.total_cmp(&a.strain.p99().0));
    for p in panels {
        writeln!(
            out,
            "| {} | {} | {:.2} / {:.2} | {:.2} / {:.2} | {} | {} |",
            p.panel,
            p.triangles,
            p.strain.p99_warp,
            p.strain.p99_weft,
            p.strain.max_warp,
            p.strain.max_weft,
            p.self_intersections,
            p.body_intersections
        )?;
    }
    Ok(())
}

/// What was done about a stall, as the last cell of its row.
fn then_said(s: &SeamStall) -> String {
    match s.then {
        StallThen::FrictionReleased => {
            "the body's friction and the hold on the panels' height let go, for the panels to slide round it"
                .to_string()
        }
        StallThen::Pulled => format!("pull at {} times full from then on", s.pull_factor),
        StallThen::Welded => {
            format!("welded where they stood (pull at {} times full)", s.pull_factor)
        }
        StallThen::Zipped => {
            let ring = s.ring_asks.map_or(String::new(), |asks| {
                format!("; the way round the body through it, {}", closing_said(asks))
            });
            format!(
                "nothing between the open pairs' sides: drawn together and welded (pull at {} times full){ring}",
                s.pull_factor
            )
        }
        StallThen::StartedOver => format!(
            "the body between its own sides: sewn again from the placed panels with every seam clear as placed drawn shut first and held shut (pull at {} times full)",
            s.pull_factor
        ),
        StallThen::FromClearEnd => {
            "the body across its sides as placed: pulled shut from its clear end joined to another seam, a pair at a time, each once the one before had closed (gap as placed)"
                .to_string()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zipped_stall_says_what_closing_asked_of_the_way_round_the_body() {
        let zipped = |ring_asks| SeamStall {
            step: 177,
            seam: "panel 'right_sleeve_f', edge 1 to panel 'right_sleeve_b', edge 3".into(),
            gap: 0.0263,
            pull_factor: 1024.0,
            then: StallThen::Zipped,
            ring_asks,
        };
        let said = then_said(&zipped(Some(0.634)));
        assert!(
            said.starts_with(
                "nothing between the open pairs' sides: drawn together and welded (pull at 1024 times full)"
            ),
            "{said}"
        );
        assert!(
            said.ends_with("; the way round the body through it, which closing stretches 63 %"),
            "{said}"
        );
        let said = then_said(&zipped(Some(-0.04)));
        assert!(
            said.ends_with("; the way round the body through it, with 4 % to spare when closed"),
            "{said}"
        );
        let said = then_said(&zipped(None));
        assert!(said.ends_with("(pull at 1024 times full)"), "{said}");
    }
}
