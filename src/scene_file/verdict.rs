//! Whether a finished garment is one a user can take as it is: at rest, nothing through
//! itself or the body, and no more stretched than a woven fabric sits on a body (the
//! measure GarmentCode's corpus is judged by here). Where it is not, why, naming the
//! panels to look at, so every garment that is not clean says so with its reason.

use super::fit::Fit;
use super::panel_report::PanelReport;
use super::report::{RunOutcome, StageReport};
use super::strain_summary::StrainSummary;

/// The 99th percentile of warp or weft strain a clean garment stays under, %.
pub const CLEAN_P99_STRAIN: f64 = 5.0;

/// The most panels named for each reason.
const NAMED: usize = 3;

/// What is said of a garment that ended clean.
pub const CLEAN: &str = "clean";

/// What each reason a garment is not clean begins with, in the order a verdict gives them
/// (each followed by ": " and its figures).
const NOT_AT_REST: &str = "not at rest";
const THROUGH_ITSELF: &str = "through itself";
const THROUGH_THE_BODY: &str = "through the body";
pub const STRETCHED: &str = "stretched";
pub const REASONS: [&str; 4] = [NOT_AT_REST, THROUGH_ITSELF, THROUGH_THE_BODY, STRETCHED];

/// The verdict on a garment's run: `None` if it did not finish (its failure says why),
/// else [`CLEAN`] or its reasons, joined by "; ". A stretched garment's reason ends with
/// what its cut asks where it is most stretched, if `fit` measured it.
pub fn verdict(
    outcome: &RunOutcome,
    stages: &[StageReport],
    self_intersections: usize,
    body_intersections: usize,
    strain: &StrainSummary,
    panels: &[PanelReport],
    fit: Option<&Fit>,
) -> Option<String> {
    if *outcome != RunOutcome::Finished {
        return None;
    }
    let mut reasons = Vec::new();
    if let Some(last) = stages.last().filter(|s| s.ended != "at_rest") {
        reasons.push(format!(
            "{NOT_AT_REST}: the {} ended at its step limit after {} steps",
            last.stage, last.steps
        ));
    }
    // ", by panel: 'a' 5, 'b' 3", the panels with any, most first; empty if none has.
    let named = |count: &dyn Fn(&PanelReport) -> usize| {
        let mut by: Vec<(&str, usize)> = panels
            .iter()
            .map(|p| (p.panel.as_str(), count(p)))
            .filter(|&(_, n)| n > 0)
            .collect();
        by.sort_by_key(|&(_, n)| std::cmp::Reverse(n));
        let most: Vec<String> = by.iter().take(NAMED).map(|(p, n)| format!("'{p}' {n}")).collect();
        if most.is_empty() {
            String::new()
        } else {
            format!(", by panel: {}", most.join(", "))
        }
    };
    if self_intersections > 0 {
        reasons.push(format!(
            "{THROUGH_ITSELF}: {self_intersections} edge-triangle pairs{}",
            named(&|p| p.self_intersections)
        ));
    }
    if body_intersections > 0 {
        reasons.push(format!(
            "{THROUGH_THE_BODY}: {body_intersections} crossings{}",
            named(&|p| p.body_intersections)
        ));
    }
    let (p99, thread) = strain.p99();
    if p99 >= CLEAN_P99_STRAIN {
        let mut tight: Vec<&PanelReport> = panels
            .iter()
            .filter(|p| p.strain.p99().0 >= CLEAN_P99_STRAIN)
            .collect();
        tight.sort_by(|a, b| b.strain.p99().0.total_cmp(&a.strain.p99().0));
        let most: Vec<String> = tight
            .iter()
            .take(NAMED)
            .map(|p| format!("'{}' {:.1} % {}", p.panel, p.strain.p99().0, p.strain.p99().1))
            .collect();
        let whole = format!("{STRETCHED}: p99 {thread} strain {p99:.1} %, over {CLEAN_P99_STRAIN} %");
        let mut reason = if most.is_empty() {
            whole
        } else {
            format!("{whole} (most: {})", most.join(", "))
        };
        if let Some(fit) = fit {
            reason += &format!(", {}", fit.said());
        }
        reasons.push(reason);
    }
    Some(if reasons.is_empty() {
        CLEAN.to_string()
    } else {
        reasons.join("; ")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stage(ended: &'static str) -> StageReport {
        StageReport {
            stage: "draping",
            steps: 40,
            seconds: 1.0,
            cg_iterations: 100,
            steps_cut: 0,
            retries: 0,
            ended,
        }
    }

    fn strain(p99_warp: f64, p99_weft: f64) -> StrainSummary {
        StrainSummary {
            max_warp: p99_warp + 1.0,
            max_weft: p99_weft + 1.0,
            p99_warp,
            p99_weft,
        }
    }

    fn panel(name: &str, p99_weft: f64, through: usize) -> PanelReport {
        PanelReport {
            panel: name.into(),
            triangles: 100,
            strain: strain(0.5, p99_weft),
            self_intersections: through,
            body_intersections: 0,
        }
    }

    #[test]
    fn at_rest_with_nothing_through_and_under_five_percent_is_clean() {
        let panels = [panel("front", 4.9, 0), panel("back", 2.0, 0)];
        let v = verdict(
            &RunOutcome::Finished,
            &[stage("at_rest")],
            0,
            0,
            &strain(1.0, 4.9),
            &panels,
            None,
        );
        assert_eq!(v.as_deref(), Some(CLEAN));
    }

    #[test]
    fn a_garment_that_is_not_clean_says_every_reason_and_names_the_panels() {
        let panels = [
            panel("bodice", 1.0, 0),
            panel("skirt_front", 9.5, 3),
            panel("skirt_back", 7.3, 5),
        ];
        let fit = Fit {
            panel: "skirt_front".into(),
            thread: "weft",
            at: [0.0, -0.1, 0.9],
            cloth_at_rest: 0.916,
            cloth_worn: 0.969,
            body_girth: 0.960,
            asks: 100.0 * (0.960 / 0.916 - 1.0),
        };
        let v = verdict(
            &RunOutcome::Finished,
            &[stage("step_limit")],
            5,
            2,
            &strain(0.5, 8.0),
            &panels,
            Some(&fit),
        )
        .unwrap();
        assert!(
            v.contains("not at rest: the draping ended at its step limit after 40 steps"),
            "{v}"
        );
        // The panels through the cloth, most first; those through the body.
        assert!(
            v.contains("through itself: 5 edge-triangle pairs, by panel: 'skirt_back' 5, 'skirt_front' 3"),
            "{v}"
        );
        assert!(v.contains("through the body: 2 crossings;"), "{v}");
        // Stretched: the whole, then the panels over the bound, most first; the bodice not.
        assert!(
            v.contains("stretched: p99 weft strain 8.0 %, over 5 % (most: 'skirt_front' 9.5 % weft, 'skirt_back' 7.3 % weft), where most stretched ('skirt_front'), 91.6 cm of cloth at rest goes round 96.0 cm of body: the cut asks 4.8 %"),
            "{v}"
        );
        assert!(!v.contains("bodice"), "{v}");
    }

    #[test]
    fn a_run_that_did_not_finish_has_its_failure_not_a_verdict() {
        let failed = RunOutcome::Failed {
            stage: "sewing",
            step: 10,
            error: "seams".into(),
        };
        assert_eq!(
            verdict(&failed, &[stage("failed")], 0, 0, &strain(0.0, 0.0), &[], None),
            None
        );
    }
}
