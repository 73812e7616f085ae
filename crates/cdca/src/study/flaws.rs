//! The flaws generator: one flaw, or a pair of equal parallel flaws in one
//! of five layouts, centred in the specimen as the held-out pairs of
//! `docs/fracture-model.md` were drawn (and to the same bits).
//!
//! A pair: the first flaw from `a0 = 0` to `a1 = L e`, `e = (cos β, sin β)`;
//! the bridge from `a1` to the second flaw's first end `b0 = a1 + b L d`
//! (`b` the bridge over the flaw length); the second flaw `b0 → b1 = b0 + L e`.
//! The bridge's direction `d` names the layout:
//!
//! | layout | d | |
//! | --- | --- | --- |
//! | `coplanar` | e | along the flaws |
//! | `stepped` | (−0.177, 0.984) | up and slightly back, as the bundled stepped pair |
//! | `overlapping` | (0.2, −0.98) | down across the flaws: a restraining step-over of the faces' left-lateral slip |
//! | `overlapping_mirrored` | (0.2, −0.98) reflected across the first flaw's line | a releasing step-over |
//! | `overlapping_across_the_load` | (cos 120°, sin 120°) | the inner ends overlap across the load (bridging angle above 90°) |
//!
//! The directions are the held-out script's numbers, not unit vectors
//! (|d| = 0.9998 stepped, 1.0002 overlapping): `b` is the bridge over the
//! flaw length to within 0.02%. The four ends' bounding box is centred on
//! the specimen's centre plus `offset` element sizes.
//!
//! `single`: one flaw of length L at β, its midpoint at the specimen's
//! centre plus `offset` element sizes, ends `c ∓ (L/2) e` (the flaw range's
//! flaw: `docs/fracture-model.md`, *The whole range, grown to failure*).

use serde::{Deserialize, Serialize};

use crate::scene::CrackSpec;

/// How the flaws lie.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Layout {
    Single,
    Coplanar,
    Stepped,
    Overlapping,
    OverlappingMirrored,
    OverlappingAcrossTheLoad,
}

impl Layout {
    pub const ALL: [Self; 6] = [
        Self::Single,
        Self::Coplanar,
        Self::Stepped,
        Self::Overlapping,
        Self::OverlappingMirrored,
        Self::OverlappingAcrossTheLoad,
    ];

    /// As study files spell it (`"overlapping_mirrored"`).
    pub const fn name(self) -> &'static str {
        match self {
            Self::Single => "single",
            Self::Coplanar => "coplanar",
            Self::Stepped => "stepped",
            Self::Overlapping => "overlapping",
            Self::OverlappingMirrored => "overlapping_mirrored",
            Self::OverlappingAcrossTheLoad => "overlapping_across_the_load",
        }
    }

    /// As the docs' tables say it (`"overlapping, mirrored"`).
    pub const fn label(self) -> &'static str {
        match self {
            Self::OverlappingMirrored => "overlapping, mirrored",
            Self::OverlappingAcrossTheLoad => "overlapping, across the load",
            other => other.name(),
        }
    }

    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|l| l.name() == name)
    }
}

/// The generator's inputs for one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flaws {
    pub layout: Layout,
    /// m
    pub length: f64,
    pub angle_deg: f64,
    pub friction: f64,
    pub bridge_over_flaw: f64,
    /// The centre's offset from the specimen's, element sizes.
    pub offset_elements: [f64; 2],
}

impl Default for Flaws {
    /// The bundled pairs' values: 3 mm flaws at 45°, μ 0.5, a bridge of
    /// one flaw length; stepped.
    fn default() -> Self {
        Self {
            layout: Layout::Stepped,
            length: 3e-3,
            angle_deg: 45.0,
            friction: 0.5,
            bridge_over_flaw: 1.0,
            offset_elements: [0.0, 0.0],
        }
    }
}

impl Flaws {
    /// The flaws' end points, m, in a specimen `width × height` with
    /// element size `h`.
    pub fn ends(&self, width: f64, height: f64, h: f64) -> Vec<[[f64; 2]; 2]> {
        let unit = |deg: f64| [deg.to_radians().cos(), deg.to_radians().sin()];
        let e = unit(self.angle_deg);
        let centre = [
            0.5 * width + self.offset_elements[0] * h,
            0.5 * height + self.offset_elements[1] * h,
        ];
        let length = self.length;
        let d = match self.layout {
            Layout::Single => {
                let d = [0.5 * length * e[0], 0.5 * length * e[1]];
                return vec![[
                    [centre[0] - d[0], centre[1] - d[1]],
                    [centre[0] + d[0], centre[1] + d[1]],
                ]];
            }
            Layout::Coplanar => e,
            Layout::Stepped => [-0.177, 0.984],
            Layout::Overlapping => [0.2, -0.98],
            Layout::OverlappingMirrored => {
                // (0.2, −0.98) reflected across the line at β
                let (c, s) = (
                    (2.0 * self.angle_deg.to_radians()).cos(),
                    (2.0 * self.angle_deg.to_radians()).sin(),
                );
                let d = [0.2, -0.98];
                [c * d[0] + s * d[1], s * d[0] - c * d[1]]
            }
            Layout::OverlappingAcrossTheLoad => unit(120.0),
        };
        let bridge = self.bridge_over_flaw * length;
        let a0 = [0.0, 0.0];
        let a1 = [length * e[0], length * e[1]];
        let b0 = [a1[0] + bridge * d[0], a1[1] + bridge * d[1]];
        let b1 = [b0[0] + length * e[0], b0[1] + length * e[1]];
        let points = [a0, a1, b0, b1];
        let mid = |k: usize| {
            let lo = points.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
            let hi = points
                .iter()
                .map(|p| p[k])
                .fold(f64::NEG_INFINITY, f64::max);
            0.5 * (lo + hi)
        };
        let (cx, cy) = (mid(0), mid(1));
        // (centre + p) − c, in the script's order of operations
        let shift = |p: [f64; 2]| [centre[0] + p[0] - cx, centre[1] + p[1] - cy];
        vec![[shift(a0), shift(a1)], [shift(b0), shift(b1)]]
    }

    /// The flaws as a scene's cracks: the ends, the friction, every other
    /// face property at its default (no cohesion, the penalty joint).
    pub fn cracks(&self, width: f64, height: f64, h: f64) -> Vec<CrackSpec> {
        self.ends(width, height, h)
            .into_iter()
            .map(|[a, b]| CrackSpec {
                points: Some(vec![a, b]),
                arc: None,
                friction: self.friction,
                cohesion: 0.0,
                normal_stiffness: None,
                shear_stiffness: None,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stepped pair of 3 mm flaws at 45°: both flaws of length L, the
    /// bridge b L |d| between the facing ends, the four ends' bounding box
    /// centred on the specimen's centre.
    #[test]
    fn a_stepped_pair_is_centred_with_its_bridge() {
        let dist = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
        let f = Flaws::default();
        let e = f.ends(0.03, 0.03, 3e-4);
        assert!((dist(e[0][0], e[0][1]) - 3e-3).abs() < 1e-15);
        assert!((dist(e[1][0], e[1][1]) - 3e-3).abs() < 1e-15);
        let bridge = dist(e[0][1], e[1][0]);
        assert!(
            (bridge - 3e-3 * 0.177_f64.hypot(0.984)).abs() < 1e-15,
            "{bridge}"
        );
        // the bounding box's centre is the specimen's
        let xs = e.iter().flatten().map(|p| p[0]);
        let (lo, hi) = xs.fold((1.0_f64, 0.0_f64), |(a, b), x| (a.min(x), b.max(x)));
        assert!((0.5 * (lo + hi) - 0.015).abs() < 1e-15);
    }

    /// Mirrored across the first flaw's line: the second flaw's first end
    /// is the overlapping one's reflected (same distance from the line,
    /// other side); across the load, the bridge runs at 120°.
    #[test]
    fn the_overlapping_layouts_differ_by_their_bridge() {
        let at = |layout| {
            let f = Flaws {
                layout,
                angle_deg: 50.0,
                ..Flaws::default()
            };
            let e = f.ends(0.03, 0.03, 3e-4);
            [e[1][0][0] - e[0][1][0], e[1][0][1] - e[0][1][1]]
        };
        let n = [-(50.0_f64.to_radians().sin()), 50.0_f64.to_radians().cos()];
        let side = |d: [f64; 2]| d[0] * n[0] + d[1] * n[1];
        let (o, m) = (at(Layout::Overlapping), at(Layout::OverlappingMirrored));
        assert!((side(o) + side(m)).abs() < 1e-15 && side(o) < 0.0);
        let a = at(Layout::OverlappingAcrossTheLoad);
        assert!((a[1].atan2(a[0]).to_degrees() - 120.0).abs() < 1e-9);
        let c = at(Layout::Coplanar);
        assert!(side(c).abs() < 1e-15);
    }

    /// One flaw: its midpoint where the offset puts it, its length L.
    #[test]
    fn a_single_flaw_sits_at_the_offset_centre() {
        let f = Flaws {
            layout: Layout::Single,
            length: 3.5e-3,
            angle_deg: 30.0,
            offset_elements: [0.37, 0.21],
            ..Flaws::default()
        };
        let h = 0.03 / 60.0;
        let [[a, b]] = f.ends(0.03, 0.03, h)[..] else {
            panic!("one flaw")
        };
        assert!((0.5 * (a[0] + b[0]) - (0.015 + 0.37 * h)).abs() < 1e-15);
        assert!((0.5 * (a[1] + b[1]) - (0.015 + 0.21 * h)).abs() < 1e-15);
        assert!(((b[0] - a[0]).hypot(b[1] - a[1]) - 3.5e-3).abs() < 1e-15);
        assert_eq!(
            Layout::from_name("overlapping_mirrored"),
            Some(Layout::OverlappingMirrored)
        );
        assert_eq!(
            Layout::OverlappingAcrossTheLoad.label(),
            "overlapping, across the load"
        );
    }
}
