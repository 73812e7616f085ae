//! One point of a parameter study (`cdca sweep`, the workbench's Study
//! tab): how and at what load the first crack starts to grow.

use super::state::Simulation;
use crate::error::SolveError;
use crate::report::Mode;
use crate::scene::{GrowthControl, Scene};

/// The first critical-growth step of a scene (SPEC §9, critical control):
/// the tip that grows first, how, and at which load factor.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Initiation {
    /// λ_cr of the first step (to the search's
    /// [`LAMBDA_TOLERANCE`](super::LAMBDA_TOLERANCE)).
    pub lambda_cr: f64,
    /// The growing tip (the first one when several grow at λ_cr): its crack
    /// and end (0 first point, 1 last); `None` when nothing grows up to
    /// `growth.max_load_factor` (then `mode` is [`Mode::None`]).
    pub tip: Option<(usize, usize)>,
    pub mode: Mode,
    /// Initial propagation angle: the new segment's angle to the crack's
    /// own direction at that tip, degrees (SPEC §8).
    pub angle_deg: f64,
    /// K_I and K_II of that tip at λ_cr, Pa·√m.
    pub k1: f64,
    pub k2: f64,
    /// Whether every solve converged and the search closed its bracket.
    pub converged: bool,
}

/// The first critical-growth step of `scene` (with `growth.control` taken
/// as critical whatever the scene says): a root search on λ through the
/// contact solve, then the growing tip's mode, angle and SIFs at λ_cr.
pub fn initiation(scene: &Scene) -> Result<Initiation, SolveError> {
    let scene = scene.edit(|s| s.growth.control = GrowthControl::Critical)?;
    let mut sim = Simulation::new(scene)?;
    let step = sim.grow_step()?;
    let first = step.grown.first();
    Ok(Initiation {
        lambda_cr: step.load_factor,
        tip: first.map(|g| (g.crack, g.tip)),
        mode: first.map_or(Mode::None, |g| g.mode),
        angle_deg: first.map_or(0.0, |g| g.angle_deg),
        k1: first.map_or(0.0, |g| g.k1),
        k2: first.map_or(0.0, |g| g.k2),
        converged: step.converged,
    })
}
