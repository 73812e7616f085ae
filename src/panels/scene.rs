//! Scene parameters: specimen and mesh, material, boundary, cracks,
//! criterion and growth. Only what the current scene can use is shown.

use cdca::fracture::criterion::radius_and_strength;
use cdca::scene::SceneFile;
use cdca::scene::{
    CriterionKind, Fix, GrowthControl, IntactRock, Material, Plane, PointSupport, Sampling,
    ShearStrength, SideBc,
};
use egui::{CollapsingHeader, Grid, Ui};

use super::widgets::{EditTracker, Typed, choice, count_row, optional_row, quantity_row};
use crate::panels::typed;
use crate::results::solution::{SolutionView, polyline_length};
use crate::state::command::Command;
use crate::state::edit::{Editor, Tool};
use crate::style::units::{self, MM_PER_M, PA_PER_GPA, PA_PER_MPA};

const MM: f64 = 1.0 / MM_PER_M;

pub fn scene_ui(
    ui: &mut Ui,
    scene: &SceneFile,
    solution: &SolutionView,
    editor: &mut Editor,
    cmds: &mut Vec<Command>,
) {
    let mut draft = scene.clone();
    let mut t = EditTracker::default();
    ui.heading("Scene");
    ui.horizontal(|ui| {
        let l = ui.label("Name");
        ui.text_edit_singleline(&mut draft.name).labelled_by(l.id);
    });
    // the scene file's own words on what it models (the bundled scenes say
    // what their run does); closed at first, it would push the fields down
    if !scene.description.is_empty() {
        CollapsingHeader::new("About this scene")
            .default_open(false)
            .show(ui, |ui| {
                ui.label(&scene.description);
            });
    }
    specimen_ui(ui, &mut draft, &mut t);
    material_ui(ui, &mut draft, &mut t);
    boundary_ui(ui, &mut draft, &mut t);
    cracks_ui(ui, &mut draft, solution, editor, &mut t);
    criterion_ui(ui, &mut draft, &mut t);
    growth_ui(ui, &mut draft, &mut t);
    if let Some(refusal) = t
        .typed
        .take()
        .and_then(|typed| refused(scene, &draft, typed))
    {
        // the scene stays as it was: the field shows its old value again
        cmds.push(Command::Refuse(refusal));
    } else if draft != *scene {
        cmds.push(Command::SetScene {
            scene: Box::new(draft),
            ongoing: t.ongoing,
        });
    } else if t.ended {
        cmds.push(Command::EndDrag);
    }
}

/// Why the value typed this frame is refused: not a number; else the
/// solver crate's rules on the scene it makes (their words come first);
/// else the field's own range.
fn refused(scene: &SceneFile, draft: &SceneFile, typed: Typed) -> Option<String> {
    if !typed.in_scene {
        return typed.refused;
    }
    typed::refusal(scene, draft, &typed.name, &typed.kept).or(typed.refused)
}

fn specimen_ui(ui: &mut Ui, s: &mut SceneFile, t: &mut EditTracker) {
    CollapsingHeader::new("Specimen and mesh")
        .default_open(true)
        .show(ui, |ui| {
            Grid::new("specimen").num_columns(2).show(ui, |ui| {
                quantity_row(ui, t, "Width", &mut s.specimen.width, MM, "mm", 1.0..=1e5);
                quantity_row(ui, t, "Height", &mut s.specimen.height, MM, "mm", 1.0..=1e5);
                quantity_row(
                    ui,
                    t,
                    "Thickness",
                    &mut s.specimen.thickness,
                    MM,
                    "mm",
                    1e-3..=1e5,
                );
                count_row(ui, t, "Elements along x", &mut s.mesh.nx, 1..=800);
                count_row(ui, t, "Elements along y", &mut s.mesh.ny, 1..=800);
                ui.label("Element size");
                ui.label(units::mm(s.element_size()));
                ui.end_row();
            });
            choice(
                ui,
                "Plane",
                &mut s.material.plane,
                &[
                    (Plane::Stress, "plane stress"),
                    (Plane::Strain, "plane strain"),
                ],
            );
        });
}

fn material_ui(ui: &mut Ui, s: &mut SceneFile, t: &mut EditTracker) {
    // which settings the criterion reads: the solver crate's one rule
    let comprehensive = s.criterion.kind.fields().shear_strength;
    // K_IIC sets the faces' shear strength on r0, c_c + K_IIC/√(2π r0)
    let shear_toughness =
        comprehensive && s.criterion.shear_strength.unwrap_or_default() == ShearStrength::Faces;
    CollapsingHeader::new("Material")
        .default_open(true)
        .show(ui, |ui| {
            Grid::new("material").num_columns(2).show(ui, |ui| {
                let m = &mut s.material;
                quantity_row(
                    ui,
                    t,
                    "Young's modulus E",
                    &mut m.young,
                    PA_PER_GPA,
                    "GPa",
                    1e-6..=1e4,
                );
                quantity_row(
                    ui,
                    t,
                    "Poisson's ratio ν",
                    &mut m.poisson,
                    1.0,
                    "",
                    -0.99..=0.499,
                );
                quantity_row(
                    ui,
                    t,
                    "Toughness K_IC",
                    &mut m.k_ic,
                    PA_PER_MPA,
                    "MPa·√m",
                    1e-6..=1e3,
                );
                if shear_toughness {
                    quantity_row(
                        ui,
                        t,
                        "Shear toughness K_IIC",
                        &mut m.k_iic,
                        PA_PER_MPA,
                        "MPa·√m",
                        1e-6..=1e3,
                    );
                }
                if comprehensive {
                    quantity_row(
                        ui,
                        t,
                        "Rock cohesion c",
                        &mut m.cohesion,
                        PA_PER_MPA,
                        "MPa",
                        0.0..=1e4,
                    );
                    quantity_row(
                        ui,
                        t,
                        "Friction angle φ",
                        &mut m.friction_angle_deg,
                        1.0,
                        "°",
                        0.0..=89.0,
                    );
                }
            });
        });
}

fn side_ui(ui: &mut Ui, t: &mut EditTracker, name: &str, bc: &mut SideBc) {
    let mut kind = match bc {
        SideBc::Free => 0,
        SideBc::Fixed => 1,
        SideBc::Roller => 2,
        SideBc::Traction { .. } => 3,
    };
    let before = kind;
    choice(
        ui,
        name,
        &mut kind,
        &[(0, "free"), (1, "fixed"), (2, "roller"), (3, "traction")],
    );
    if kind != before {
        *bc = match kind {
            1 => SideBc::Fixed,
            2 => SideBc::Roller,
            3 => SideBc::Traction {
                normal: -1e6,
                shear: 0.0,
            },
            _ => SideBc::Free,
        };
    }
    if let SideBc::Traction { normal, shear } = bc {
        t.group = Some(name.to_owned());
        Grid::new(("traction", name)).num_columns(2).show(ui, |ui| {
            quantity_row(
                ui,
                t,
                "  normal (tension +)",
                normal,
                PA_PER_MPA,
                "MPa",
                -1e5..=1e5,
            );
            quantity_row(ui, t, "  shear", shear, PA_PER_MPA, "MPa", -1e5..=1e5);
        });
        t.group = None;
    }
}

fn boundary_ui(ui: &mut Ui, s: &mut SceneFile, t: &mut EditTracker) {
    CollapsingHeader::new("Loads and supports")
        .default_open(true)
        .show(ui, |ui| {
            let b = &mut s.boundary;
            side_ui(ui, t, "Top", &mut b.top);
            side_ui(ui, t, "Right", &mut b.right);
            side_ui(ui, t, "Bottom", &mut b.bottom);
            side_ui(ui, t, "Left", &mut b.left);
            let mut remove = None;
            for (i, p) in b.points.iter_mut().enumerate() {
                let fix = match p.fix {
                    Fix::X => "x",
                    Fix::Y => "y",
                    Fix::Xy => "x, y",
                };
                let title = format!(
                    "Point support {}: ({}, {}) mm, fixes {fix}",
                    i + 1,
                    units::compact(p.at[0] * MM_PER_M),
                    units::compact(p.at[1] * MM_PER_M)
                );
                CollapsingHeader::new(title)
                    .id_salt(("point support", i))
                    .show(ui, |ui| {
                        t.group = Some(format!("Point support {}", i + 1));
                        Grid::new("point").num_columns(2).show(ui, |ui| {
                            quantity_row(ui, t, "x", &mut p.at[0], MM, "mm", -1e5..=1e5);
                            quantity_row(ui, t, "y", &mut p.at[1], MM, "mm", -1e5..=1e5);
                        });
                        t.group = None;
                        choice(
                            ui,
                            "fixes",
                            &mut p.fix,
                            &[(Fix::X, "x"), (Fix::Y, "y"), (Fix::Xy, "x and y")],
                        )
                        .on_hover_text("The node nearest to the point is held in this direction");
                        if ui
                            .small_button(format!("Remove support {}", i + 1))
                            .clicked()
                        {
                            remove = Some(i);
                        }
                    });
            }
            if ui
                .small_button("Add point support")
                .on_hover_text("A support at the bottom-left corner, fixing x; edit where and what")
                .clicked()
            {
                b.points.push(PointSupport {
                    at: [0.0, 0.0],
                    fix: Fix::X,
                });
            }
            if let Some(i) = remove {
                b.points.remove(i);
            }
        });
}

fn cracks_ui(
    ui: &mut Ui,
    s: &mut SceneFile,
    solution: &SolutionView,
    editor: &mut Editor,
    t: &mut EditTracker,
) {
    let h = s.element_size();
    // SPEC §5 default: k_N = 100 E / h.
    let penalty = 100.0 * s.material.young / h;
    // Friction and cohesion act only where faces touch: hide them once a
    // solve has shown every face point open.
    let faces_closed = !solution.all_faces_open();
    CollapsingHeader::new(format!("Cracks ({})", s.cracks.len()))
        .default_open(true)
        .show(ui, |ui| {
            if ui.button("Draw a new crack").clicked() {
                editor.tool = Tool::DrawCrack;
                editor.drawing.clear();
            }
            if !faces_closed {
                ui.weak("All crack faces are open: friction and cohesion have no effect.");
            }
            let mut remove = None;
            for (i, crack) in s.cracks.iter_mut().enumerate() {
                let selected = editor.selected_crack == Some(i);
                let polyline = crack.polyline(h);
                let title = format!(
                    "Crack {}: {} points, {}",
                    i + 1,
                    polyline.len(),
                    units::mm(polyline_length(&polyline))
                );
                CollapsingHeader::new(title)
                    .id_salt(("crack", i))
                    .default_open(selected)
                    .show(ui, |ui| {
                        t.group = Some(format!("Crack {}", i + 1));
                        if faces_closed {
                            Grid::new(("crack grid", i)).num_columns(2).show(ui, |ui| {
                                quantity_row(
                                    ui,
                                    t,
                                    "Friction μ",
                                    &mut crack.friction,
                                    1.0,
                                    "",
                                    0.0..=5.0,
                                );
                                quantity_row(
                                    ui,
                                    t,
                                    "Face cohesion c_c",
                                    &mut crack.cohesion,
                                    PA_PER_MPA,
                                    "MPa",
                                    0.0..=1e4,
                                );
                                optional_row(
                                    ui,
                                    t,
                                    "Normal k_N",
                                    &mut crack.normal_stiffness,
                                    penalty,
                                    PA_PER_GPA,
                                    "GPa/m",
                                );
                                let kt = crack.normal_stiffness.unwrap_or(penalty) / 10.0;
                                optional_row(
                                    ui,
                                    t,
                                    "Shear k_T",
                                    &mut crack.shear_stiffness,
                                    kt,
                                    PA_PER_GPA,
                                    "GPa/m",
                                );
                            });
                        }
                        // typed geometry, for a class exercise with exact points
                        if let Some(points) = crack.points.as_mut() {
                            CollapsingHeader::new("Points (mm)")
                                .id_salt(("crack points", i))
                                .show(ui, |ui| {
                                    Grid::new(("points grid", i)).num_columns(2).show(ui, |ui| {
                                        for (k, p) in points.iter_mut().enumerate() {
                                            quantity_row(
                                                ui,
                                                t,
                                                &format!("point {} x", k + 1),
                                                &mut p[0],
                                                MM,
                                                "mm",
                                                -1e5..=1e5,
                                            );
                                            quantity_row(
                                                ui,
                                                t,
                                                &format!("point {} y", k + 1),
                                                &mut p[1],
                                                MM,
                                                "mm",
                                                -1e5..=1e5,
                                            );
                                        }
                                    });
                                });
                        }
                        t.group = None;
                        grown_from_ui(ui, solution, i);
                        ui.horizontal(|ui| {
                            if ui
                                .selectable_label(selected, format!("Select crack {}", i + 1))
                                .clicked()
                            {
                                editor.selected_crack = if selected { None } else { Some(i) };
                            }
                            if ui.button(format!("Delete crack {}", i + 1)).clicked() {
                                remove = Some(i);
                            }
                        });
                    });
            }
            if let Some(i) = remove {
                s.cracks.remove(i);
                editor.selected_crack = None;
            }
            rock_cracks_ui(ui, solution);
        });
}

/// The cracks a run started at flaw `flaw`'s kinks (secondary cracks), by
/// the plots' names, with their lengths; nothing before a run.
fn grown_from_ui(ui: &mut Ui, solution: &SolutionView, flaw: usize) {
    let rows: Vec<String> = solution
        .lineage
        .iter()
        .enumerate()
        .filter(|(_, l)| l.drawn == 0 && !l.is_intact() && l.flaw == flaw)
        .map(|(c, _)| grown_row(solution, c))
        .collect();
    if !rows.is_empty() {
        ui.label("Grown from it in the run:");
        for row in rows {
            ui.weak(row);
        }
    }
}

/// The cracks a run started in the intact rock, in a group of their own.
fn rock_cracks_ui(ui: &mut Ui, solution: &SolutionView) {
    let rows: Vec<String> = solution
        .lineage
        .iter()
        .enumerate()
        .filter(|(_, l)| l.is_intact())
        .map(|(c, _)| grown_row(solution, c))
        .collect();
    if !rows.is_empty() {
        CollapsingHeader::new(format!("Started in the intact rock ({})", rows.len()))
            .id_salt("rock cracks")
            .show(ui, |ui| {
                for row in rows {
                    ui.weak(row);
                }
            });
    }
}

/// "Crack 1 · secondary 1: 2.100 mm".
fn grown_row(solution: &SolutionView, c: usize) -> String {
    let length = solution.cracks.get(c).map_or(0.0, |p| polyline_length(p));
    format!("{}: {}", solution.crack_name(c), units::mm(length))
}

fn criterion_ui(ui: &mut Ui, s: &mut SceneFile, t: &mut EditTracker) {
    CollapsingHeader::new("Fracture criterion")
        .default_open(false)
        .show(ui, |ui| {
            let c = &mut s.criterion;
            choice(
                ui,
                "Criterion",
                &mut c.kind,
                &[
                    (CriterionKind::Comprehensive, "tension, then shear (paper)"),
                    (CriterionKind::Mts, "max. tangential stress"),
                    (CriterionKind::MtsT, "MTS with T-stress"),
                ],
            );
            // a new kind keeps only the settings it reads (the scene would
            // refuse the others); the rows below show only those
            *c = c.with_kind(c.kind);
            let fields = c.kind.fields();
            Grid::new("criterion").num_columns(2).show(ui, |ui| {
                let (auto_r0, _) = radius_and_strength(None, &s.material);
                if fields.r0 {
                    optional_row(ui, t, "Radius r0", &mut c.r0, auto_r0, MM, "mm");
                }
                if fields.sampling {
                    let without = Material {
                        tensile_strength: None,
                        ..s.material.clone()
                    };
                    let (_, auto) = radius_and_strength(c.r0, &without);
                    optional_row(
                        ui,
                        t,
                        "Tensile strength σ_t",
                        &mut s.material.tensile_strength,
                        auto,
                        PA_PER_MPA,
                        "MPa",
                    );
                }
            });
            if fields.r0 && c.r0.is_none() {
                ui.weak(
                    "auto r0: the process zone above, or a/5π on a crack of \
                     half-length a shorter than 5π times it (σ_t then rises so \
                     that mode I still needs K_IC); the tip inspector shows \
                     each tip's r0",
                );
            }
            if fields.sampling {
                let mut sampling = c.sampling.unwrap_or_default();
                choice(
                    ui,
                    "Sampling",
                    &mut sampling,
                    &[
                        (Sampling::Hybrid, "K-field + face stress"),
                        (Sampling::Field, "computed field"),
                        (Sampling::Williams, "Williams expansion"),
                    ],
                );
                if sampling != c.sampling.unwrap_or_default() {
                    c.sampling = Some(sampling);
                }
            }
            if fields.shear_strength {
                let mut shear = c.shear_strength.unwrap_or_default();
                choice(
                    ui,
                    "Shear strength",
                    &mut shear,
                    &[
                        (ShearStrength::Faces, "faces' μ, c + K_IIC"),
                        (ShearStrength::Rock, "rock's φ, c"),
                    ],
                );
                if shear != c.shear_strength.unwrap_or_default() {
                    c.shear_strength = Some(shear);
                }
            }
        });
}

fn growth_ui(ui: &mut Ui, s: &mut SceneFile, t: &mut EditTracker) {
    let (r0, _) = radius_and_strength(s.criterion.r0, &s.material);
    let r0 = cdca::fracture::growth::default_increment(r0, s.element_size());
    CollapsingHeader::new("Growth")
        .default_open(false)
        .show(ui, |ui| {
            choice(
                ui,
                "Control",
                &mut s.growth.control,
                &[
                    (GrowthControl::Critical, "to failure (λ_cr per step)"),
                    (GrowthControl::Load, "load ramp to the scene's load"),
                ],
            );
            choice(
                ui,
                "Intact rock",
                &mut s.growth.intact_rock,
                &[
                    (IntactRock::Nucleate, "fails: cracks start in it"),
                    (IntactRock::Ignore, "never fails (the paper's model)"),
                ],
            )
            .on_hover_text(
                "growth.intact_rock. \"nucleate\": where the rock's Mohr–Coulomb envelope with \
                 its tension cut-off, read over a disc of radius r0, is met below every tip's \
                 and kink's load, a new crack starts there. \"ignore\": the paper's model, \
                 only crack tips and kinks grow.",
            );
            Grid::new("growth").num_columns(2).show(ui, |ui| {
                let g = &mut s.growth;
                optional_row(ui, t, "Increment Δa", &mut g.increment, r0, MM, "mm");
                // only the settings the chosen control uses
                match g.control {
                    GrowthControl::Load => {
                        count_row(ui, t, "Load steps", &mut g.load_steps, 1..=10_000);
                        count_row(
                            ui,
                            t,
                            "Max growth per load step",
                            &mut g.max_growth_per_step,
                            1..=10_000,
                        );
                    }
                    GrowthControl::Critical => quantity_row(
                        ui,
                        t,
                        "Max load factor λ",
                        &mut g.max_load_factor,
                        1.0,
                        "",
                        1e-6..=1e6,
                    ),
                }
                count_row(ui, t, "Max steps", &mut g.max_steps, 1..=100_000);
                ui.label("Secondary cracks");
                let r = ui
                    .checkbox(&mut g.secondary_cracks, "start at sharp kinks")
                    .on_hover_text(
                        "A crack's sharp kinks (a flaw's end that a wing has left) are sites of \
                         the criterion, read on r0 from the field: where it is met a new crack \
                         starts there (growth.secondary_cracks). Off: only free tips grow.",
                    );
                t.track(&r);
                ui.end_row();
            });
        });
}
