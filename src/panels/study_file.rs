//! The Study tab's *Study file* mode: a study file (bundled, or opened
//! like a scene), how much of it to run with the time that should take,
//! run / cancel / export; then its map per layout (or its plots over one
//! axis), each at least 300 px tall, or its rows in a table whose header
//! stays in view (below the maps the table sat under the fold, its header
//! scrolling away with its rows).

use egui::{ProgressBar, Ui};
use egui_extras::{Column, TableBuilder};

use crate::plots::figure::Figure;
use crate::state::command::{Command, Export};
use crate::state::view::AppView;
use crate::study::file::{
    BUNDLED_STUDIES, FileStudy, LoadedStudy, MapColour, StudyFileSetup, input_text,
};
use crate::style::units;

/// Height of one figure (legend, plot and its axes), px: the plot itself
/// keeps about 300.
const FIGURE_HEIGHT: f32 = 330.0;

/// Draws figure `index` as every plot is drawn (the plot panel's, with
/// its legend and its CSV and SVG buttons).
pub type FigureUi<'a> = &'a dyn Fn(&mut Ui, usize, &Figure, &mut Vec<Command>);

pub fn study_file_ui(
    ui: &mut Ui,
    v: &AppView,
    setup: &mut StudyFileSetup,
    cmds: &mut Vec<Command>,
    figure: FigureUi<'_>,
) {
    let running = v.file_study.is_some_and(|s| !s.finished());
    ui.horizontal_wrapped(|ui| {
        mode_ui(ui, setup);
        ui.separator();
        let label = ui.label("Study to run");
        let chosen = v.loaded_study.map_or("choose one", |l| l.source.as_str());
        egui::ComboBox::from_id_salt("study file")
            .selected_text(chosen)
            .show_ui(ui, |ui| {
                for b in BUNDLED_STUDIES {
                    if ui.selectable_label(chosen == b.file, b.title).clicked() {
                        cmds.push(Command::OpenStudy {
                            source: b.file.to_owned(),
                            text: b.json.to_owned(),
                        });
                    }
                }
            })
            .response
            .labelled_by(label.id);
        if ui
            .button("Open…")
            .on_hover_text(
                "A study file of your own (File > Open and a file dropped on the window open one too)",
            )
            .clicked()
        {
            cmds.push(Command::OpenDialog);
        }
        if let Some(loaded) = v.loaded_study {
            describe(ui, loaded);
        }
    });
    let Some(loaded) = v.loaded_study else {
        ui.weak("A study file holds a base scene and axes; cdca study runs the same files on every core (docs/studies.md). Choose one above.");
        return;
    };
    ui.horizontal_wrapped(|ui| {
        ui.radio_value(&mut setup.first_steps, true, "First steps of every point");
        ui.radio_value(&mut setup.first_steps, false, "Grow the first");
        ui.add_enabled(
            !setup.first_steps,
            egui::DragValue::new(&mut setup.cap).range(1..=loaded.study.points().len().max(1)),
        );
        ui.label("points to the end");
        ui.separator();
        let runs = setup.points(&loaded.study).len();
        ui.label(format!(
            "{runs} runs, about {}",
            units::seconds(setup.estimate_seconds(&loaded.study))
        ))
        .on_hover_text("Before it starts, from the mesh size and the steps: a first step about 70 µs per element natively (its λ search solves several times), a later step 14 µs, twice that in the browser; a run to the end is taken as 40 steps. Once points finish, the progress bar says the time left from their own times.");
    });
    ui.horizontal_wrapped(|ui| {
        if ui
            .add_enabled(!running, egui::Button::new("Run study file"))
            .clicked()
        {
            cmds.push(Command::RunStudyFile(setup.clone()));
        }
        if ui
            .add_enabled(running, egui::Button::new("Cancel"))
            .clicked()
        {
            cmds.push(Command::CancelStudy);
        }
        if ui
            .add_enabled(
                v.file_study.is_some_and(|s| !s.rows.is_empty()),
                egui::Button::new("Table as CSV…"),
            )
            .on_hover_text("The rows as cdca study writes them")
            .clicked()
        {
            cmds.push(Command::Export(Export::StudyTable));
        }
        if let Some(run) = v.file_study {
            ui.add(
                ProgressBar::new(run.progress())
                    .desired_width(180.0)
                    .text(format!(
                        "{} of {} points{}",
                        run.rows.len(),
                        run.planned(),
                        if run.cancelled() {
                            " (cancelled)".to_owned()
                        } else {
                            run.seconds_left().map_or_else(String::new, |s| {
                                format!(", about {} left", units::seconds(s))
                            })
                        }
                    )),
            );
            let label = ui.label("Colour");
            egui::ComboBox::from_id_salt("study map colour")
                .selected_text(colour_words(setup.colour))
                .show_ui(ui, |ui| {
                    for c in [MapColour::Cracks, MapColour::Link, MapColour::Peak] {
                        ui.selectable_value(&mut setup.colour, c, colour_words(c));
                    }
                })
                .response
                .labelled_by(label.id);
        }
    });
    let Some(run) = v.file_study else {
        return;
    };
    ui.horizontal(|ui| {
        ui.selectable_value(&mut setup.table, false, "Maps");
        ui.selectable_value(&mut setup.table, true, "Table");
    });
    if setup.table {
        rows_table(ui, run);
        return;
    }
    let figs = run.figures(setup.colour);
    egui::ScrollArea::vertical()
        .id_salt("study file scroll")
        .show(ui, |ui| {
            let gap = ui.spacing().item_spacing.x;
            let per_row = if figs.len() > 1 { 2 } else { 1 };
            let width = (ui.available_width() - gap * (per_row - 1) as f32) / per_row as f32;
            let down = egui::Layout::top_down(egui::Align::Min);
            for (r, chunk) in figs.chunks(per_row).enumerate() {
                ui.horizontal_top(|ui| {
                    for (c, fig) in chunk.iter().enumerate() {
                        let index = r * per_row + c;
                        ui.allocate_ui_with_layout(egui::vec2(width, FIGURE_HEIGHT), down, |ui| {
                            ui.set_width(width);
                            ui.set_height(FIGURE_HEIGHT);
                            ui.push_id(index, |ui| figure(ui, index, fig, cmds));
                        });
                    }
                });
            }
        });
}

/// What a map's colours show, in words.
fn colour_words(c: MapColour) -> &'static str {
    match c {
        MapColour::Cracks => "the cracks that grew",
        MapColour::Link => "what the first link joins",
        MapColour::Peak => "the peak λ",
    }
}

/// The tab's two modes: a sweep of one field, or a study file.
pub fn mode_ui(ui: &mut Ui, setup: &mut StudyFileSetup) {
    ui.selectable_value(&mut setup.use_file, false, "Sweep one field");
    ui.selectable_value(&mut setup.use_file, true, "Study file");
}

/// The study's points and axes, in a few words; its name, description
/// and hash on hover.
fn describe(ui: &mut Ui, loaded: &LoadedStudy) {
    let s = &loaded.study;
    // the axes as the map and the table name them (a field's path read
    // `flaws.angle_deg`); the paths on hover
    let axes: Vec<String> = s
        .axes
        .iter()
        .map(|a| crate::study::map::axis_label(a).0)
        .collect();
    let text = format!(
        "{} points, {} over {}",
        s.points().len(),
        format!("{:?}", s.combine).to_lowercase(),
        axes.join(" × ")
    );
    ui.add(egui::Label::new(egui::RichText::new(text).weak()).truncate())
        .on_hover_text(format!(
            "{}: {} (study {}; axes {})",
            s.name,
            s.description,
            s.short_hash(),
            s.axes
                .iter()
                .map(|a| a.field.as_str())
                .collect::<Vec<_>>()
                .join(" × ")
        ));
}

/// The columns after a row's inputs.
const COLUMNS: [&str; 8] = [
    "outcome",
    "steps",
    "peak λ [–]",
    "first link",
    "step",
    "wings",
    "secondary",
    "rock cracks",
];

/// The rows: point, inputs, outcome, steps, peak λ, first link, wings,
/// secondary cracks and cracks started in the intact rock, under a header
/// that stays in view; the table scrolls sideways as a whole (a study of
/// many axes is wider than the panel).
fn rows_table(ui: &mut Ui, run: &FileStudy) {
    let axes = &run.study.axes;
    // the axes as the map names them, in the UI's units (the header read
    // `flaws.angle_deg`), the field's path on hover
    let titles: Vec<(String, f64)> = axes.iter().map(crate::study::map::axis_label).collect();
    let row_height = ui.text_style_height(&egui::TextStyle::Body) + 4.0;
    egui::ScrollArea::horizontal()
        .id_salt("study file rows")
        .show(ui, |ui| {
            TableBuilder::new(ui)
                .id_salt("study file table")
                .striped(true)
                .columns(Column::auto(), 1 + axes.len() + COLUMNS.len())
                .header(row_height, |mut header| {
                    header.col(|ui| {
                        ui.strong("point");
                    });
                    for ((title, _), axis) in titles.iter().zip(axes) {
                        header.col(|ui| {
                            ui.strong(title).on_hover_text(axis.field.as_str());
                        });
                    }
                    for h in COLUMNS {
                        header.col(|ui| {
                            ui.strong(h);
                        });
                    }
                })
                .body(|body| {
                    body.rows(row_height, run.rows.len(), |mut cells| {
                        let row = &run.rows[cells.index()];
                        let mut cell = |text: String, hover: Option<&str>| {
                            cells.col(|ui| {
                                let label = ui.label(text);
                                if let Some(why) = hover {
                                    label.on_hover_text(why);
                                }
                            });
                        };
                        cell(row.point.to_string(), None);
                        for (input, (_, factor)) in row.inputs.iter().zip(&titles) {
                            cell(input_text(input, *factor), None);
                        }
                        // the outcome says on hover why a point failed
                        cell(row.outcome.clone(), row.error.as_deref());
                        let rest: [String; 7] = match &row.run {
                            None => std::array::from_fn(|_| "–".to_owned()),
                            Some(r) => {
                                let (joins, step) = r
                                    .link
                                    .as_ref()
                                    .map_or(("none".to_owned(), "–".to_owned()), |l| {
                                        (l.category.clone(), l.step.to_string())
                                    });
                                [
                                    r.steps.to_string(),
                                    r.strength.as_ref().map_or("–".to_owned(), |s| {
                                        format!("{:.3}", s.peak_load_factor)
                                    }),
                                    joins,
                                    step,
                                    r.wings.to_string(),
                                    r.secondary_cracks.to_string(),
                                    r.intact_rock_cracks.to_string(),
                                ]
                            }
                        };
                        for text in rest {
                            cell(text, None);
                        }
                    });
                });
        });
}
