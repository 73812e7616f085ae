//! The tip inspector: K_I, K_II, T, the criterion's decision, and a polar
//! plot of σ_θθ(θ, r0) and |τ_rθ(θ, r0)| with their thresholds and the
//! chosen angle.

use cdca::CriterionCurve;
use cdca::report::{Mode, TipReport};
use cdca::scene::SceneFile;
use egui::{Color32, Grid, Ui};
use egui_plot::{Line, LineStyle, Plot, PlotPoints};

use crate::panels::plots::swatch;
use crate::plots::figure::Style;
use crate::run::RunMode;
use crate::state::command::Command;
use crate::state::view::AppView;
use crate::style::units;

const SIGMA_COLOR: Color32 = Color32::from_rgb(70, 140, 255);
const TAU_COLOR: Color32 = Color32::from_rgb(255, 150, 40);
const ANGLE_COLOR: Color32 = Color32::from_rgb(40, 200, 90);

/// The polar plot's name for assistive technology (and the UI tests).
const POLAR_PLOT_LABEL: &str = "Polar plot of σ_θθ and |τ_rθ| on r0";

/// Largest side of the polar plot, px.
const MAX_POLAR_SIDE: f32 = 320.0;

/// Width kept beside the polar plot for its key, px.
const KEY_WIDTH: f32 = 110.0;

/// Smallest side of the polar plot, px: with less room left above the
/// window's bottom the panel scrolls to it.
const MIN_POLAR_SIDE: f32 = 160.0;

pub fn tip_ui(ui: &mut Ui, v: &AppView, cmds: &mut Vec<Command>) {
    ui.heading("Tip inspector");
    if let Some(snapshot) = v.replayed {
        replayed_tips_ui(ui, snapshot);
        return;
    }
    let tips = &v.solution.tips;
    if tips.is_empty() {
        let sol = &v.solution;
        ui.weak(if sol.split {
            "No free tip: the final cracks cut the specimen through."
        } else if v.run.mode != RunMode::Paused {
            "A run is in progress: the tips show when it ends."
        } else if !sol.solved {
            "Solve, then click a tip on the canvas."
        } else if v.scene.cracks.is_empty() {
            "No crack: draw one to inspect its tips."
        } else {
            "No free tip: every crack end meets a boundary or another crack."
        });
        return;
    }
    let name = |i: usize| {
        let t = &tips[i];
        format!("{}, end {}", v.solution.crack_name(t.crack), t.tip + 1)
    };
    let mut selected = v.selected_tip;
    egui::ComboBox::from_label("Tip")
        .selected_text(
            selected
                .filter(|&i| i < tips.len())
                .map_or_else(|| "none".to_owned(), name),
        )
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut selected, None, "none");
            for i in 0..tips.len() {
                ui.selectable_value(&mut selected, Some(i), name(i));
            }
        });
    if selected != v.selected_tip {
        cmds.push(Command::SelectTip(selected));
    }
    let Some(tip) = v.selected_tip.and_then(|i| tips.get(i)) else {
        return;
    };
    values_ui(ui, tip);
    match v.tip_curve {
        Some(c) => polar_plot_ui(ui, v.scene, tip, c),
        None => {
            ui.weak("No σ_θθ / τ_rθ curve for this tip.");
        }
    }
}

/// A replayed step's tips as that step's solve had them, named as the
/// cracks were then (the run's end named cracks that did not yet exist).
fn replayed_tips_ui(ui: &mut Ui, snapshot: &crate::results::replay::Snapshot) {
    let view = &snapshot.view;
    ui.label(format!(
        "Replaying step {}: the free tips of its solve at λ = {:.3}.",
        snapshot.step, view.load_factor
    ));
    if view.tips.is_empty() {
        ui.weak("No tips were kept for this step.");
        return;
    }
    // a tip's name, then its values and decision wrapped to the panel: as
    // a table of four columns they ran past a Solver panel of 260 points
    for t in &view.tips {
        ui.strong(format!("{}, end {}", view.crack_name(t.crack), t.tip + 1));
        ui.add(
            egui::Label::new(format!(
                "K_I {}, K_II {}: {}",
                k1_words(t),
                units::mpa_sqrt_m(t.k2),
                decision_words(t)
            ))
            .wrap(),
        );
    }
}

/// The criterion's decision; "grows in tension" beside closed faces says
/// why (the sliding faces' K_II pulls the rock beside the tip apart: a
/// wing), which read as a contradiction next to "K_I ≈ 0 (faces closed)".
fn decision_words(tip: &TipReport) -> String {
    let at = units::deg(tip.criterion.angle_deg);
    match tip.criterion.mode {
        Mode::Tension if closed(tip) => {
            format!("grows in tension at {at}: sliding (K_II) pulls the rock there apart")
        }
        Mode::Tension => format!("grows in tension at {at}"),
        Mode::Shear => format!("grows in shear at {at}"),
        Mode::None => "does not grow".to_owned(),
    }
}

fn values_ui(ui: &mut Ui, tip: &TipReport) {
    Grid::new("tip values").num_columns(2).show(ui, |ui| {
        let rows = [
            (
                "Position",
                format!("({}, {})", units::mm(tip.x), units::mm(tip.y)),
            ),
            ("K_I", k1_words(tip)),
            ("K_II", units::mpa_sqrt_m(tip.k2)),
            ("T-stress", units::mpa(tip.t_stress)),
            ("Decision", decision_words(tip)),
            ("Angle", units::deg(tip.criterion.angle_deg)),
            ("max σ_θθ on r0", units::mpa(tip.criterion.sigma_theta_max)),
            ("max |τ_rθ| on r0", units::mpa(tip.criterion.tau_max)),
        ];
        for (k, v) in rows {
            ui.label(k);
            let shown = ui.label(v);
            if k == "K_I" && tip.k1 != 0.0 {
                shown.on_hover_text(format!("computed {}", units::mpa_sqrt_m(tip.k1)));
            }
            ui.end_row();
        }
    });
}

/// K_I with a word where it is only round-off: on closed faces K_I is
/// zero up to the discretisation (−0.0056 MPa·√m against K_II = 2.8 on
/// the default flaw, 0.2 %), and a negative K_I beside "grows in tension"
/// read as a contradiction. Below 1 % of |K_II| in magnitude it is shown
/// as "≈ 0 (faces closed)", the computed value on hover.
fn k1_words(tip: &TipReport) -> String {
    if closed(tip) {
        "≈ 0 (faces closed)".to_owned()
    } else {
        units::mpa_sqrt_m(tip.k1)
    }
}

/// K_I is round-off on closed faces: negative and below 1 % of |K_II|.
fn closed(tip: &TipReport) -> bool {
    tip.k1 < 0.0 && tip.k1.abs() < 0.01 * tip.k2.abs()
}

/// Polar coordinates with the radius shifted so every plotted value is
/// non-negative: ρ(v) = v − base (base ≤ every value and ≤ 0).
fn polar(theta_deg: &[f64], values: impl Iterator<Item = f64>, base: f64) -> PlotPoints<'static> {
    theta_deg
        .iter()
        .zip(values)
        .map(|(&th, v)| {
            let r = (v - base) * 1e-6;
            let a = th.to_radians();
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

fn circle(radius: f64) -> PlotPoints<'static> {
    (0..=120)
        .map(|k| {
            let a = f64::from(k) / 120.0 * std::f64::consts::TAU;
            [radius * a.cos(), radius * a.sin()]
        })
        .collect()
}

fn polar_plot_ui(ui: &mut Ui, scene: &SceneFile, tip: &TipReport, c: &CriterionCurve) {
    // a criterion with a shear branch (the solver crate says which)
    let comprehensive = scene.criterion.kind.fields().shear_strength;
    let tau_abs: Vec<f64> = c.tau_rt.iter().map(|t| t.abs()).collect();
    // empty where the shear branch does not apply (open faces at the tip)
    let tau_limit: Vec<f64> = c
        .shear_envelope
        .map_or_else(Vec::new, |(friction, cohesion)| {
            c.sigma_tt
                .iter()
                .map(|s| (-s).max(0.0) * friction + cohesion)
                .collect()
        });
    let base = c
        .sigma_tt
        .iter()
        .chain(&tau_abs)
        .copied()
        .chain([0.0, c.sigma_t])
        .fold(0.0_f64, f64::min)
        * 1.05;
    let outer = c
        .sigma_tt
        .iter()
        .chain(&tau_abs)
        .chain(&tau_limit)
        .copied()
        .fold(c.sigma_t, f64::max)
        - base;
    // base ≤ 0: the radius is the value shifted out by |base|
    let shift = if base < 0.0 {
        format!(" + {}", units::mpa(-base))
    } else {
        String::new()
    };
    ui.label(format!(
        "On r0 = {}, θ = 0 straight ahead, radius = value{shift}:",
        units::mm(c.r0),
    ));
    if comprehensive && c.shear_envelope.is_none() {
        ui.weak("Shear branch off: the faces at this tip are open.");
    }
    // the key beside the plot: inside it would cover the curves, and above
    // it took the height the plot needs
    let shear = comprehensive && !tau_limit.is_empty();
    let chosen = tip.criterion.mode != Mode::None;
    let key = [
        ("σ_θθ", SIGMA_COLOR, Style::Line, true),
        ("σ_t", SIGMA_COLOR, Style::Dashed, true),
        ("0 MPa", Color32::GRAY, Style::Dashed, true),
        ("|τ_rθ|", TAU_COLOR, Style::Line, shear),
        ("shear limit", TAU_COLOR, Style::Dashed, shear),
        ("chosen angle", ANGLE_COLOR, Style::Line, chosen),
    ];
    // square, no taller than the room left in the panel's view (it ran
    // past the bottom of a 1400 × 900 window), with the outermost curve
    // inside
    let room = ui.clip_rect().bottom() - ui.cursor().top() - ui.spacing().item_spacing.y;
    let side = (ui.available_width() - KEY_WIDTH - ui.spacing().item_spacing.x)
        .min(MAX_POLAR_SIDE)
        .min(room)
        .max(MIN_POLAR_SIDE);
    let reach = outer * 1e-6 * 1.05;
    // beside the plot where there is room for the key, else under it (a
    // Solver panel at its least width cut "shear limit" at the window)
    let beside = ui.available_width() >= side + KEY_WIDTH + ui.spacing().item_spacing.x;
    let layout = if beside {
        egui::Layout::left_to_right(egui::Align::TOP)
    } else {
        egui::Layout::top_down(egui::Align::Min)
    };
    ui.with_layout(layout, |ui| {
        let shown = Plot::new("polar")
            .data_aspect(1.0)
            .width(side)
            .height(side)
            .include_x(-reach)
            .include_x(reach)
            .include_y(-reach)
            .include_y(reach)
            .show_axes(false)
            .show_grid(false)
            .show(ui, |plot| {
                plot.line(
                    Line::new("0 MPa", circle(-base * 1e-6))
                        .color(Color32::GRAY)
                        .style(LineStyle::dashed_dense()),
                );
                plot.line(
                    Line::new(
                        "σ_θθ",
                        polar(&c.theta_deg, c.sigma_tt.iter().copied(), base),
                    )
                    .color(SIGMA_COLOR)
                    .width(2.0),
                );
                plot.line(
                    Line::new("σ_t", circle((c.sigma_t - base) * 1e-6))
                        .color(SIGMA_COLOR)
                        .style(LineStyle::dashed_loose()),
                );
                if shear {
                    plot.line(
                        Line::new("|τ_rθ|", polar(&c.theta_deg, tau_abs.iter().copied(), base))
                            .color(TAU_COLOR)
                            .width(2.0),
                    );
                    plot.line(
                        Line::new(
                            "shear limit",
                            polar(&c.theta_deg, tau_limit.iter().copied(), base),
                        )
                        .color(TAU_COLOR)
                        .style(LineStyle::dashed_loose()),
                    );
                }
                if chosen {
                    let a = tip.criterion.angle_deg.to_radians();
                    let r = outer * 1e-6;
                    plot.line(
                        Line::new(
                            "chosen angle",
                            PlotPoints::from(vec![[0.0, 0.0], [r * a.cos(), r * a.sin()]]),
                        )
                        .color(ANGLE_COLOR)
                        .width(2.5),
                    );
                }
            });
        shown
            .response
            .widget_info(|| egui::WidgetInfo::labeled(egui::Role::Figure, true, POLAR_PLOT_LABEL));
        let shown_key = key.into_iter().filter(|k| k.3);
        if beside {
            ui.vertical(|ui| {
                for (name, colour, style, _) in shown_key {
                    ui.horizontal(|ui| {
                        swatch(ui, colour, Some(style));
                        ui.label(name);
                    });
                }
            });
        } else {
            // each entry moves to the next row whole
            ui.horizontal_wrapped(|ui| {
                for (name, colour, style, _) in shown_key {
                    swatch(ui, colour, Some(style));
                    ui.add(egui::Label::new(name).extend());
                }
            });
        }
    });
}
