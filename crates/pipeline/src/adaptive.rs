//! Adaptive sampling of one swept parameter: a stage declares the range a figure shows
//! and a tolerance, and its points are refined where the curve bends or peaks.
//!
//! ```yaml
//! V0: {adaptive: {logspace: [-3, 3, 13], y: mu_star, tol: 0.01}}
//! #   optional: log_y: true, levels: 3 (halvings of the initial spacing), max_points: 97
//! ```
//! Round 0 computes the initial grid. After each round, every curve (the points that share
//! the values of the other parameters) is examined in the sampling coordinate t (log10 of
//! the parameter for `logspace`): a point whose `y` lies further than `tol` times the
//! curve's span of `y` from the chord of its two neighbours marks the two intervals beside
//! it, and each marked interval gets its midpoint, largest deviations first, until no point
//! deviates, the spacing has been halved `levels` times, or the curve has `max_points`.
//! Points that did not converge (a `converged` column that is false) take no part.
//!
//! The choice is a function of the computed outputs only, and new values are rounded to
//! 12 significant digits, so a rerun reproduces the same points (and finds them cached),
//! and each point is an ordinary, content-addressed task: changing `tol` reuses every
//! point already computed. A dry run follows the rounds as far as the cache answers them.

use crate::kind::{DynKind, Output};
use crate::spec::{label_token, round12, AdaptiveAxis, Point};
use serde_json::Value;
use std::collections::BTreeMap;

impl AdaptiveAxis {
    /// The sampling coordinate of a parameter value.
    pub fn coord(&self, x: f64) -> f64 {
        if self.log {
            x.log10()
        } else {
            x
        }
    }

    /// The parameter value at a sampling coordinate, rounded to 12 significant digits.
    pub fn value(&self, t: f64) -> f64 {
        round12(if self.log { 10f64.powf(t) } else { t })
    }

    /// The smallest spacing refinement may reach.
    pub fn min_step(&self) -> f64 {
        let initial = if self.initial > 1 { (self.to - self.from).abs() / (self.initial - 1) as f64 } else { 0.0 };
        initial / 2f64.powi(self.levels as i32)
    }
}

/// One sample of a curve: its coordinate and its y values (None: not usable, e.g. not
/// converged).
#[derive(Clone, Debug)]
pub struct Sample {
    pub t: f64,
    pub y: Option<Vec<f64>>,
}

/// The new coordinates to sample on one curve (sorted), given what it has.
pub fn refine(axis: &AdaptiveAxis, samples: &[Sample]) -> Vec<f64> {
    let mut s: Vec<&Sample> = samples.iter().collect();
    s.sort_by(|a, b| a.t.total_cmp(&b.t));
    let room = axis.max_points.saturating_sub(s.len());
    if room == 0 || s.len() < 3 {
        return Vec::new();
    }
    let ys: Vec<Option<Vec<f64>>> = s
        .iter()
        .map(|p| {
            p.y.as_ref().and_then(|v| {
                let w: Vec<f64> = v.iter().map(|&y| if axis.log_y { y.log10() } else { y }).collect();
                w.iter().all(|y| y.is_finite()).then_some(w)
            })
        })
        .collect();
    let n_cols = ys.iter().flatten().map(|v| v.len()).max().unwrap_or(0);
    let span: Vec<f64> = (0..n_cols)
        .map(|c| {
            let vals = ys.iter().flatten().map(|v| v[c]);
            let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| (lo.min(y), hi.max(y)));
            hi - lo
        })
        .collect();
    // Largest deviation flagging each interval [i, i + 1] of the sorted samples.
    let mut flag = vec![0.0f64; s.len() - 1];
    for i in 1..s.len() - 1 {
        let (Some(a), Some(b), Some(c)) = (&ys[i - 1], &ys[i], &ys[i + 1]) else { continue };
        let w = (s[i].t - s[i - 1].t) / (s[i + 1].t - s[i - 1].t);
        let dev = (0..n_cols)
            .filter(|&k| span[k] > 0.0)
            .map(|k| (b[k] - (a[k] + w * (c[k] - a[k]))).abs() / span[k])
            .fold(0.0, f64::max);
        if dev > axis.tol {
            flag[i - 1] = flag[i - 1].max(dev);
            flag[i] = flag[i].max(dev);
        }
    }
    let min_step = axis.min_step();
    let mut candidates: Vec<(f64, f64)> = flag
        .iter()
        .enumerate()
        .filter(|(i, &dev)| dev > 0.0 && (s[i + 1].t - s[*i].t) / 2.0 >= min_step * (1.0 - 1e-6))
        .map(|(i, &dev)| (dev, 0.5 * (s[i].t + s[i + 1].t)))
        .collect();
    candidates.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.total_cmp(&b.1)));
    let mut out: Vec<f64> = candidates.into_iter().take(room).map(|(_, t)| t).collect();
    out.sort_by(f64::total_cmp);
    out
}

/// Why adaptive sampling cannot place a stage's next points.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AdaptiveError {
    #[error("adaptive sampling of `{param}` reads the column `{column}`, which the points' tables do not have (columns: {})", present.join(", "))]
    MissingColumn { param: String, column: String, present: Vec<String> },
    #[error("adaptive sampling of `{param}` needs one row per point; a point has {rows}")]
    Rows { param: String, rows: usize },
    #[error("adaptive sampling of `{param}`: the column `{column}` is not numeric")]
    NotNumeric { param: String, column: String },
    #[error("adaptive sampling: the point {label} has no numeric `{param}`")]
    NoValue { param: String, label: String },
    #[error("adaptive sampling: the new point {param}={value} is invalid: {errors}")]
    InvalidPoint { param: String, value: f64, errors: String },
}

/// The y values of one point's output, if usable: one row, the columns present and
/// finite, and not flagged as not converged. An error names a missing column.
fn point_y(axis: &AdaptiveAxis, out: &Output) -> Result<Option<Vec<f64>>, AdaptiveError> {
    let t = &out.table;
    let mut y = Vec::with_capacity(axis.y.len());
    for name in &axis.y {
        let Some(col) = t.column(name) else {
            return Err(AdaptiveError::MissingColumn {
                param: axis.param.clone(),
                column: name.clone(),
                present: t.column_names(),
            });
        };
        if t.n_rows() != 1 {
            return Err(AdaptiveError::Rows { param: axis.param.clone(), rows: t.n_rows() });
        }
        match col.f64_at(0) {
            Some(v) => y.push(v),
            None => return Err(AdaptiveError::NotNumeric { param: axis.param.clone(), column: name.clone() }),
        }
    }
    let converged = t.column("converged").and_then(|c| c.f64_at(0)).is_none_or(|c| c != 0.0);
    Ok(converged.then_some(y))
}

/// The curve a point belongs to: its parameters without the adaptive one.
fn curve_of(axis: &AdaptiveAxis, params: &Value) -> String {
    let mut p = params.clone();
    if let Some(m) = p.as_object_mut() {
        m.remove(&axis.param);
    }
    p.to_string()
}

/// The points to add to a stage after a round, given all its points and their outputs
/// (same order). New points are checked (and made canonical) by the stage's kind.
pub fn next_points(
    axis: &AdaptiveAxis,
    kind: &dyn DynKind,
    points: &[Point],
    outputs: &[&Output],
) -> Result<Vec<Point>, AdaptiveError> {
    let mut curves: BTreeMap<String, (usize, Vec<Sample>)> = BTreeMap::new();
    for (i, (p, o)) in points.iter().zip(outputs).enumerate() {
        let x = p
            .params
            .get(&axis.param)
            .and_then(Value::as_f64)
            .ok_or_else(|| AdaptiveError::NoValue { param: axis.param.clone(), label: p.label.clone() })?;
        let y = point_y(axis, o)?;
        curves.entry(curve_of(axis, &p.params)).or_insert((i, Vec::new())).1.push(Sample { t: axis.coord(x), y });
    }
    let mut by_first: Vec<(usize, Vec<Sample>)> = curves.into_values().collect();
    by_first.sort_by_key(|(i, _)| *i);
    let mut new = Vec::new();
    for (first, samples) in by_first {
        let template = &points[first];
        for t in refine(axis, &samples) {
            let x = axis.value(t);
            let mut value = template.params.clone();
            value.as_object_mut().expect("params are a mapping").insert(axis.param.clone(), serde_json::json!(x));
            let (canonical, _) = kind.check(&value).map_err(|errors| {
                let e: Vec<String> = errors.iter().map(|e| format!("{}: {}", e.path, e.message)).collect();
                AdaptiveError::InvalidPoint { param: axis.param.clone(), value: x, errors: e.join("; ") }
            })?;
            new.push(Point { params: canonical, label: relabel(&template.label, &axis.param, x) });
        }
    }
    Ok(new)
}

/// A point's label with the adaptive parameter's value replaced.
fn relabel(label: &str, param: &str, x: f64) -> String {
    let prefix = format!("{param}=");
    label
        .split(' ')
        .map(|tok| if tok.starts_with(&prefix) { label_token(param, x) } else { tok.to_string() })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The order in which an adaptive stage's points are published: curve by curve (in the
/// order of their first point), along the axis within each.
pub fn publication_order(axis: &AdaptiveAxis, points: &[Point]) -> Vec<usize> {
    let mut first: BTreeMap<String, usize> = BTreeMap::new();
    let keyed: Vec<(usize, f64)> = points
        .iter()
        .map(|p| {
            let c = first.len();
            let curve = *first.entry(curve_of(axis, &p.params)).or_insert(c);
            (curve, p.params.get(&axis.param).and_then(Value::as_f64).unwrap_or(f64::NAN))
        })
        .collect();
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| keyed[a].0.cmp(&keyed[b].0).then(keyed[a].1.total_cmp(&keyed[b].1)));
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(tol: f64, levels: u32, max_points: usize) -> AdaptiveAxis {
        AdaptiveAxis {
            param: "x".into(),
            log: false,
            from: 0.0,
            to: 1.0,
            initial: 5,
            y: vec!["y".into()],
            log_y: false,
            tol,
            levels,
            max_points,
        }
    }

    /// Runs the refinement to the end on a function and returns the final coordinates.
    fn sample(a: &AdaptiveAxis, f: impl Fn(f64) -> f64) -> Vec<f64> {
        let mut ts: Vec<f64> = (0..a.initial).map(|i| a.value(a.from + (a.to - a.from) * i as f64 / 4.0)).collect();
        for _ in 0..50 {
            let s: Vec<Sample> = ts.iter().map(|&t| Sample { t, y: Some(vec![f(t)]) }).collect();
            let new = refine(a, &s);
            if new.is_empty() {
                break;
            }
            ts.extend(new.into_iter().map(|t| a.value(t)));
            ts.sort_by(f64::total_cmp);
        }
        ts
    }

    #[test]
    fn a_straight_line_is_not_refined() {
        assert_eq!(sample(&axis(0.01, 4, 100), |t| 3.0 * t - 1.0).len(), 5);
    }

    #[test]
    fn a_peak_is_resolved_to_the_tolerance_and_only_near_the_peak() {
        let peak = |t: f64| (-((t - 0.62) / 0.05).powi(2)).exp();
        let a = axis(0.02, 6, 1000);
        let ts = sample(&a, peak);
        // Much fewer points than the uniform grid of the finest spacing (257).
        assert!(ts.len() > 15 && ts.len() < 60, "{}", ts.len());
        // Refined near the peak, not far from it.
        let near = ts.iter().filter(|t| (*t - 0.62).abs() < 0.15).count();
        assert!(near as f64 > 0.7 * ts.len() as f64, "{near} of {}", ts.len());
        // Piecewise-linear interpolation of the samples: within a few tol of the curve.
        let mut worst = 0.0f64;
        for i in 0..=1000 {
            let t = i as f64 / 1000.0;
            let j = ts.partition_point(|&s| s <= t).clamp(1, ts.len() - 1);
            let w = (t - ts[j - 1]) / (ts[j] - ts[j - 1]);
            let lin = peak(ts[j - 1]) + w * (peak(ts[j]) - peak(ts[j - 1]));
            worst = worst.max((lin - peak(t)).abs());
        }
        assert!(worst < 0.06, "worst interpolation error {worst}");
        // The peak itself is found to within the final spacing near it.
        let best = ts.iter().copied().max_by(|a, b| peak(*a).total_cmp(&peak(*b))).unwrap();
        assert!((best - 0.62).abs() < 0.01, "{best}");
    }

    #[test]
    fn refinement_stops_at_the_levels_and_at_max_points() {
        let step = |t: f64| if t < 0.3 { 0.0 } else { 1.0 };
        // A jump can never meet the tolerance: the spacing floor stops it.
        let ts = sample(&axis(1e-3, 3, 1000), step);
        let min_gap = ts.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
        assert!((min_gap - 0.25 / 8.0).abs() < 1e-9, "{min_gap}");
        assert!(ts.len() <= 16, "{}", ts.len());
        assert_eq!(sample(&axis(1e-3, 10, 7), step).len(), 7);
    }

    #[test]
    fn unusable_points_take_no_part() {
        let a = axis(0.01, 3, 100);
        let mut s: Vec<Sample> = (0..5).map(|i| Sample { t: i as f64 / 4.0, y: Some(vec![(i * i) as f64]) }).collect();
        assert!(!refine(&a, &s).is_empty());
        // The only bent point not converged: nothing to refine around it.
        for i in [1, 2, 3] {
            s[i].y = None;
        }
        assert!(refine(&a, &s).is_empty());
    }

    #[test]
    fn log_coordinates_round_trip_and_labels_are_rewritten() {
        let a = AdaptiveAxis { log: true, from: -3.0, to: 3.0, initial: 13, ..axis(0.01, 3, 100) };
        assert_eq!(a.value(-1.0), 0.1);
        assert_eq!(a.value(0.25), 1.77827941004);
        assert!((a.coord(a.value(0.25)) - 0.25).abs() < 1e-11);
        assert_eq!(relabel("lambda=0.1 x=1 W=3", "x", 1.77827941004), "lambda=0.1 x=1.778279 W=3");
    }
}
