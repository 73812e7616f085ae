//! Geometry of crack growth (SPEC §9): extend a tip by Δa at the kink
//! angle; a segment that would cross another crack ends on it (junction),
//! one that would leave the specimen ends on the boundary. A tip that comes
//! within `snap` (one element, see `Simulation`'s growth) of a crack or the
//! boundary is snapped onto it: a ligament narrower than an element is not
//! resolved by the mesh (both cracks enrich the same elements), so the two
//! have linked (BACKGROUND §3.10, coalescence).

use crate::geometry::cracks::{Crack, TipFrame, first_crossing};
use crate::geometry::plane::{P2, clip_segment_to_box, closest_on_segment};

/// Default growth increment `Δa = max(r0, 3h)`: the criterion's radius, but
/// no shorter than three elements, below which a new segment and the
/// interaction-integral domain (3h) of its tip are not resolved by the mesh.
pub fn default_increment(r0: f64, h: f64) -> f64 {
    r0.max(3.0 * h)
}

/// What happened to a tip that grew.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Extension {
    /// Still free at the new point.
    Free(P2),
    /// Ended on crack `main`.
    Junction(P2, usize),
    /// Ended on the specimen boundary.
    Boundary(P2),
}

impl Extension {
    pub fn point(self) -> P2 {
        match self {
            Self::Free(p) | Self::Junction(p, _) | Self::Boundary(p) => p,
        }
    }
}

/// Where tip `k` of crack `c` goes when it grows by `da` at `angle` (rad,
/// tip frame), in a `width × height` specimen; `snap` is the distance
/// within which it is put onto a crack or the boundary.
pub fn extend(
    cracks: &[Crack],
    c: usize,
    k: usize,
    angle: f64,
    da: f64,
    width: f64,
    height: f64,
    snap: f64,
) -> Extension {
    let frame = TipFrame::of(&cracks[c], k);
    let d = frame.global(P2::new(angle.cos(), angle.sin()));
    extend_from(
        cracks,
        Some((c, k)),
        frame.origin,
        d,
        da,
        width,
        height,
        snap,
    )
}

/// Where a segment from `a` along the unit direction `d` goes when it
/// grows by `da` ([`extend`]): the tip `k` of crack `c` when `from` is
/// `Some((c, k))` (its own segment at that tip is skipped), or the first
/// segment of a crack starting at `a` (on another crack's kink, which it
/// does not cross there).
pub fn extend_from(
    cracks: &[Crack],
    from: Option<(usize, usize)>,
    a: P2,
    d: P2,
    da: f64,
    width: f64,
    height: f64,
    snap: f64,
) -> Extension {
    let reach = da + snap;
    let b = a + reach * d;
    // the first crack crossed (own crack: skip the segment at this tip)
    let mut best: Option<(f64, P2, usize)> = None;
    for (m, other) in cracks.iter().enumerate() {
        let hit = match from {
            Some((c, k)) if m == c => own_crossing(other, k, a, b),
            _ => first_crossing(other, a, b),
        };
        if let Some((s, p)) = hit
            && s * reach > 1e-9 * da
            && best.is_none_or(|(bs, _, _)| s < bs)
        {
            best = Some((s, p, m));
        }
    }
    // leaving the specimen
    let exit =
        clip_segment_to_box(a, b, P2::zeros(), P2::new(width, height)).map_or(0.0, |(_, t1)| t1);
    match best {
        Some((s, p, m)) if s <= exit => Extension::Junction(p, m),
        _ if exit < 1.0 => Extension::Boundary(a + exit * (b - a)),
        _ => {
            let p = a + da * d;
            nearest_other(cracks, from.map(|(c, _)| c), p)
                .filter(|&(q, _)| (q - p).norm() <= snap)
                .map_or(Extension::Free(p), |(q, m)| Extension::Junction(q, m))
        }
    }
}

/// The point nearest to `p` on any crack other than `c`, and that crack.
fn nearest_other(cracks: &[Crack], c: Option<usize>, p: P2) -> Option<(P2, usize)> {
    let mut best: Option<(f64, P2, usize)> = None;
    for (m, other) in cracks.iter().enumerate().filter(|&(m, _)| Some(m) != c) {
        for (s, e) in other.segments() {
            let q = s + closest_on_segment(p, s, e) * (e - s);
            let dist = (q - p).norm();
            if best.is_none_or(|(bd, _, _)| dist < bd) {
                best = Some((dist, q, m));
            }
        }
    }
    best.map(|(_, q, m)| (q, m))
}

/// First crossing of `ab` with the crack's own polyline, ignoring the
/// segment that ends at tip `k`.
fn own_crossing(crack: &Crack, k: usize, a: P2, b: P2) -> Option<(f64, P2)> {
    let n = crack.points.len();
    let skip = if k == 0 { 0 } else { n - 2 };
    let mut best: Option<(f64, P2)> = None;
    for (i, (c, d)) in crack.segments().enumerate() {
        if i == skip {
            continue;
        }
        if let Some((s, _)) = crate::geometry::plane::segment_intersection(a, b, c, d)
            && best.is_none_or(|(bs, _)| s < bs)
        {
            best = Some((s, a + s * (b - a)));
        }
    }
    best
}

/// Appends the new point at tip `k` (a grown segment).
pub fn apply(crack: &mut Crack, k: usize, p: P2) {
    if k == 0 {
        crack.points.insert(0, p);
    } else {
        crack.points.push(p);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::cracks::TipKind;

    fn crack(pts: &[[f64; 2]]) -> Crack {
        Crack::bare(pts, [TipKind::Free; 2])
    }

    #[test]
    fn growth_stops_on_another_crack_and_on_the_boundary() {
        let cracks = vec![
            crack(&[[0.2, 0.5], [0.4, 0.5]]),
            crack(&[[0.45, 0.2], [0.45, 0.8]]),
        ];
        // tip 1 of crack 0 grows straight (+x) by 0.1: crosses crack 1 at x = 0.45
        match extend(&cracks, 0, 1, 0.0, 0.1, 1.0, 1.0, 0.01) {
            Extension::Junction(p, 1) => {
                assert!((p.x - 0.45).abs() < 1e-12 && (p.y - 0.5).abs() < 1e-12);
            }
            e => panic!("{e:?}"),
        }
        // tip 0 of crack 0 grows by 0.25 (−x): leaves at x = 0
        match extend(&cracks, 0, 0, 0.0, 0.25, 1.0, 1.0, 0.01) {
            Extension::Boundary(p) => assert!(p.x.abs() < 1e-12),
            e => panic!("{e:?}"),
        }
        // a short step stays free
        assert!(matches!(
            extend(&cracks, 0, 0, 0.0, 0.05, 1.0, 1.0, 0.01),
            Extension::Free(_)
        ));
    }

    /// A tip that ends beside another crack, within the snap distance but
    /// not crossing it, ends on its nearest point (coalescence); one just
    /// outside stays free.
    #[test]
    fn a_tip_that_ends_beside_another_crack_joins_it() {
        let cracks = vec![
            crack(&[[0.2, 0.5], [0.4, 0.5]]),
            // runs parallel to the growth direction, 0.008 above its path
            crack(&[[0.45, 0.508], [0.6, 0.508]]),
        ];
        match extend(&cracks, 0, 1, 0.0, 0.1, 1.0, 1.0, 0.01) {
            Extension::Junction(p, 1) => {
                assert!(
                    (p.x - 0.5).abs() < 1e-12 && (p.y - 0.508).abs() < 1e-12,
                    "{p:?}"
                );
            }
            e => panic!("{e:?}"),
        }
        assert!(matches!(
            extend(&cracks, 0, 1, 0.0, 0.1, 1.0, 1.0, 0.007),
            Extension::Free(_)
        ));
    }
}
