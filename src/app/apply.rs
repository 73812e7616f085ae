//! Applying the UI's commands to the app: edits with undo, opening scenes,
//! solver actions and exports.

use cdca::scene::SceneFile;

use crate::app::WorkbenchApp;
use crate::files::path_prompt::{PathPrompt, PromptAction};
use crate::files::{io, scenes};
use crate::plots::figure::Figure;
use crate::plots::figures::Plotted;
use crate::plots::plot_tab::PlotTab;
use crate::state::command::{Command, Export, PlotFormat};
use crate::state::job::{Job, Waiting};
use crate::state::view::Message;
use crate::study::Study;
use crate::study::file::{FileStudy, LoadedStudy};
use crate::study::race::Race;

impl WorkbenchApp {
    pub(crate) fn run_cmd(&mut self, ctx: &egui::Context, cmd: Command) {
        // one job at a time: another job asked for while one runs waits for
        // the user to cancel the running one (a job asked for again
        // restarts or goes on, as before)
        if let (Some(wanted), Some(running)) = (Job::of_command(&cmd), self.running_job())
            && wanted != running
        {
            self.waiting = Some(Waiting {
                running,
                command: cmd,
            });
            return;
        }
        if Job::of_command(&cmd).is_some() {
            self.waiting = None;
        }
        self.follow_with_plot(&cmd);
        match cmd {
            Command::SetScene { scene, ongoing } => {
                self.dragging = ongoing;
                if *scene == self.scene {
                    if !ongoing {
                        self.undo.end_coalescing();
                    }
                    return;
                }
                self.note_edited_crack(&scene);
                if ongoing {
                    let (scene, source, opened) =
                        (&self.scene, &self.scene_source, &self.opened_scene);
                    let present = || crate::state::undo::Entry::new(scene, source, opened);
                    self.undo.record(present, true);
                } else {
                    // the run on screen (if any) is kept: Undo brings it back
                    self.record_replacing(true, false);
                }
                self.scene = *scene;
                self.scene_changed(ongoing);
            }
            Command::AddCrack(crack) => self.add_crack(ctx, *crack),
            Command::EndDrag => {
                self.dragging = false;
                self.undo.end_coalescing();
                let followed = std::mem::take(&mut self.drag_followed);
                if self.runner.is_stale() {
                    self.scene_changed(false);
                } else if followed {
                    // its last position is solved as Solve would solve it
                    self.runner.check_after_drag();
                }
            }
            Command::OpenSceneText { source, text } => self.open_scene_text(source, &text),
            Command::OpenLink(link) => self.open_link(&link),
            Command::CopyLink => self.copy_link(ctx),
            Command::OpenBundled(i) => {
                if let Some(b) = scenes::BUNDLED.get(i) {
                    self.open_scene_text(b.title.to_owned(), b.json);
                }
            }
            Command::OpenDialog => {
                let picked = if self.options.file_dialogs {
                    io::open_scene_dialog(self.last_folder.as_deref())
                } else {
                    Ok(io::Picked::NoDialog)
                };
                match picked {
                    Ok(io::Picked::Chosen(file)) => self.open_scene_text(file.name, &file.text),
                    Ok(io::Picked::Cancelled) => {}
                    Ok(io::Picked::NoDialog) => {
                        self.path_prompt = Some(PathPrompt {
                            action: PromptAction::Open,
                            path: io::default_path("", self.last_folder.as_deref()),
                        });
                    }
                    Err(e) => self.message = Some(Message::Error(e)),
                }
            }
            Command::UseTypedPath => self.use_typed_path(),
            Command::CancelTypedPath => self.path_prompt = None,
            Command::Export(what) => self.export(ctx, what),
            Command::Undo => self.undo(),
            Command::Redo => self.redo(),
            Command::Solve => {
                if self.ensure_simulation() {
                    // after growth it solves the grown cracks, at the last load
                    let grown = self.runner.is_grown();
                    let steps = self.runner.view().steps_done;
                    let kept = self.runner.solve();
                    if grown {
                        // Undo brings the run back as it ended
                        self.record_run(kept);
                        // a grown scene resumes at its last step's load
                        let lambda = self.runner.view().load_factor;
                        self.message = Some(Message::Info(format!(
                            "Solving the cracks as grown (after growth step {steps}) at the \
                                 run's last load, λ = {lambda:.3}. The run's steps stay in the \
                                 plots."
                        )));
                    }
                }
            }
            Command::Step => {
                if self.ensure_simulation() {
                    self.runner.step();
                }
            }
            Command::Relax => {
                if self.ensure_simulation() {
                    self.runner.relax();
                }
            }
            Command::GrowOne | Command::RunGrowth => {
                self.replay_step = None;
                if self.ensure_simulation() {
                    let one = matches!(cmd, Command::GrowOne);
                    self.runner.start_growth(one);
                }
            }
            Command::SetPace(pace) => self.runner.set_pace(pace),
            Command::Replay(step) => self.replay_step = step,
            Command::SetAccelerateGrowth(on) => self.runner.set_accelerate_growth(on),
            Command::RunStudy(setup) => {
                let accelerate = self.runner.accelerate_growth();
                let study = self
                    .runner
                    .checked()
                    .and_then(|base| Study::new(base, &setup.path, setup.values(), accelerate));
                match study {
                    Ok(study) => {
                        // Undo brings back the finished study this replaces
                        self.record_replacing(false, true);
                        self.study = Some(study);
                    }
                    Err(e) => {
                        self.message = Some(Message::Error(format!("The study cannot run: {e}")));
                    }
                }
            }
            Command::CancelStudy => {
                if let Some(s) = self.study.as_mut() {
                    s.cancel();
                }
                if let Some(s) = self.file_study.as_mut() {
                    s.cancel();
                }
            }
            Command::OpenStudy { source, text } => self.open_study(&source, &text),
            Command::RunStudyFile(setup) => match &self.loaded_study {
                Some(loaded) => {
                    self.study_file_setup = setup.clone();
                    self.file_study = Some(FileStudy::new(loaded, &setup));
                }
                None => {
                    self.message = Some(Message::Error(
                        "Choose or open a study file before running it.".to_owned(),
                    ));
                }
            },
            Command::Pause => self.runner.pause(),
            Command::ShowPlot(tab) => self.plot_tab = tab,
            Command::Reset => {
                // Undo brings back the run on screen
                let run = self.runner.take_run();
                self.record_run(run);
                let valid = self.runner.invalidate(&self.scene);
                self.show_validity(valid);
                self.auto_solve();
            }
            Command::CompareSolvers { time_cap } => {
                // the race's reference is the direct solution
                let checked = self.runner.checked().and_then(|s| {
                    let mut file = cdca::scene::SceneFile::clone(s);
                    file.solver.kind = cdca::scene::SolverKind::Direct;
                    crate::run::host::interactive_mesh(&file).map(|()| s)
                });
                match checked {
                    Ok(scene) => self.race = Some(Race::new(scene, time_cap)),
                    Err(e) => {
                        let e = format!("The race cannot run: {e}");
                        self.message = Some(Message::Error(e));
                    }
                }
            }
            Command::CancelRace => {
                if let Some(r) = self.race.as_mut() {
                    r.cancel();
                }
            }
            Command::SelectTip(tip) => {
                self.selected_tip = tip;
                self.no_tip_wanted = tip.is_none();
            }
            Command::DismissMessage => self.message = None,
            Command::Refuse(why) => self.message = Some(Message::Error(why)),
            Command::CancelJob => self.cancel_job(),
            Command::StartWaiting => {
                if let Some(w) = self.waiting.take() {
                    self.cancel_job();
                    self.run_cmd(ctx, w.command);
                }
            }
            Command::DropWaiting => self.waiting = None,
        }
    }

    /// Remembers which crack an edit changed (the last one changed, when
    /// the edit keeps the number of cracks): a drawn crack takes its
    /// contact law.
    fn note_edited_crack(&mut self, edited: &cdca::scene::SceneFile) {
        let (old, new) = (&self.scene.cracks, &edited.cracks);
        if old.len() == new.len()
            && let Some(i) = (0..new.len()).rev().find(|&i| old[i] != new[i])
        {
            self.last_edited_crack = Some(i);
        }
    }

    /// Adds a drawn crack with the contact law of the last edited crack
    /// (else the scene's last crack): a crack drawn beside a μ = 0.5 flaw
    /// used to get μ = 0. The banner says where its values came from.
    fn add_crack(&mut self, ctx: &egui::Context, mut crack: cdca::scene::CrackSpec) {
        let mut scene = self.scene.clone();
        let from = self
            .last_edited_crack
            .filter(|&i| i < scene.cracks.len())
            .or_else(|| scene.cracks.len().checked_sub(1));
        let n = scene.cracks.len() + 1;
        if let Some(i) = from {
            let source = &scene.cracks[i];
            crack.friction = source.friction;
            crack.cohesion = source.cohesion;
            crack.normal_stiffness = source.normal_stiffness;
            crack.shear_stiffness = source.shear_stiffness;
            self.message = Some(Message::Info(format!(
                "Crack {n} takes friction μ = {} and cohesion {} MPa from crack {}, the last \
                 edited; change them under Crack {n} in the Scene panel.",
                crack.friction,
                crack.cohesion / crate::style::units::PA_PER_MPA,
                i + 1
            )));
        }
        scene.cracks.push(crack);
        self.last_edited_crack = Some(n - 1);
        self.editor.selected_crack = Some(n - 1);
        self.run_cmd(
            ctx,
            Command::SetScene {
                scene: Box::new(scene),
                ongoing: false,
            },
        );
    }

    /// Shows the plot that fits the run a command starts: the residual for
    /// sweeps, the kink angles for growth, the race for Compare solvers
    /// (unless the command line fixed the tab, `--plot`).
    fn follow_with_plot(&mut self, cmd: &Command) {
        if self.options.plot.is_some() {
            return;
        }
        let iterative = self.scene.solver.kind != cdca::scene::SolverKind::Direct;
        self.plot_tab = match cmd {
            Command::Step | Command::Relax => PlotTab::ResidualBySweep,
            Command::Solve if iterative => PlotTab::ResidualBySweep,
            Command::GrowOne | Command::RunGrowth => PlotTab::Angles,
            Command::CompareSolvers { .. } => PlotTab::SolverComparison,
            Command::RunStudy(_) | Command::RunStudyFile(_) => PlotTab::Study,
            Command::SetScene { scene, .. } if scene.solver.kind != self.scene.solver.kind => {
                PlotTab::fitting(scene)
            }
            _ => return,
        };
    }

    /// A simulation of the current scene exists (rebuilt if the scene changed).
    fn ensure_simulation(&mut self) -> bool {
        if self.runner.is_stale() || !self.runner.has_simulation() {
            self.rebuild();
        }
        self.runner.has_simulation()
    }

    fn rebuild(&mut self) {
        self.selected_tip = None;
        self.tip_curve = None;
        let result = self.runner.rebuild(&self.scene);
        self.show_validity(result);
    }

    /// Shows why the scene cannot be simulated, or clears an old error.
    fn show_validity(&mut self, result: Result<(), String>) {
        match result {
            Ok(()) => {
                if matches!(self.message, Some(Message::Error(_))) {
                    self.message = None;
                }
            }
            Err(e) => {
                self.message = Some(Message::Error(format!(
                    "The scene cannot be simulated: {e}"
                )));
            }
        }
    }

    fn auto_solve(&mut self) {
        if self.options.auto_solve && self.runner.solve_is_quick(&self.scene) {
            self.solve_scene();
        }
    }

    /// Solves the scene now (building its simulation first if needed).
    fn solve_scene(&mut self) {
        if self.runner.is_stale() || !self.runner.has_simulation() {
            self.rebuild();
        }
        if self.runner.has_simulation() {
            // (an edit's re-solve keeps no run: an edit after growth
            // recorded it already)
            drop(self.runner.solve());
        }
    }

    /// While a drag goes on, its scene is solved whenever the last solve
    /// has ended and been shown (if the scene solves quickly): the field
    /// follows the pointer, a solve or two behind it.
    pub(crate) fn follow_drag(&mut self, ctx: &egui::Context) {
        if !(self.dragging && self.follows_drag()) {
            return;
        }
        if self.runner.follow_drag() {
            self.drag_followed = true;
            ctx.request_repaint();
        }
    }

    /// Edits re-solve unasked, and so follow a drag.
    fn follows_drag(&self) -> bool {
        self.options.auto_solve && self.runner.solve_is_quick(&self.scene)
    }

    /// The edited scene changed. While a drag goes on, the last solution
    /// stays until a solve of the dragged scene replaces it
    /// ([`follow_drag`](Self::follow_drag)), where the scene solves quickly,
    /// and is hidden otherwise; when the drag ends the simulation is
    /// rebuilt and re-solved if that is quick.
    pub(crate) fn scene_changed(&mut self, ongoing: bool) {
        self.replay_step = None;
        self.race = None;
        if ongoing && self.follows_drag() && self.runner.can_follow_drag() {
            self.runner.edit_during_drag(&self.scene);
            return;
        }
        self.selected_tip = None;
        self.tip_curve = None;
        if self
            .editor
            .selected_crack
            .is_some_and(|i| i >= self.scene.cracks.len())
        {
            self.editor.selected_crack = None;
        }
        let valid = self.runner.invalidate(&self.scene);
        if !ongoing {
            let ok = valid.is_ok();
            self.show_validity(valid);
            if ok {
                self.auto_solve();
            }
        }
    }

    /// Makes `scene` (checked) the scene being edited, with one undo step.
    fn open_scene(&mut self, source: String, scene: cdca::scene::SceneFile) {
        // Undo brings back the scene, its run and its finished study
        self.record_replacing(true, true);
        self.opened_scene = scene.clone();
        self.last_edited_crack = None;
        self.scene = scene;
        self.scene_source = source;
        self.canvas.fit_requested = true;
        self.editor = crate::state::edit::Editor::default();
        self.message = None;
        self.runner.forget_contact();
        self.no_tip_wanted = false;
        self.scene_changed(false);
        // an opened scene is shown solved whatever its size (an edit is
        // re-solved by itself only when that is quick): in slices, so no
        // frame waits for it
        if self.options.auto_solve && !self.runner.is_running() && self.runner.checked().is_ok() {
            self.solve_scene();
        }
    }

    /// Opens the scene of a shared link; a link without a valid scene opens
    /// the default scene (not the last one, which the sender never saw) and
    /// says why.
    fn open_link(&mut self, link: &str) {
        let problem = match crate::files::link::from_link(link) {
            Some(Ok(scene)) => {
                self.address.holds(scene.clone());
                self.open_scene("shared link".to_owned(), scene);
                return;
            }
            Some(Err(e)) => e,
            None => "it carries no scene (#scene=…)".to_owned(),
        };
        self.open_scene("default scene".to_owned(), scenes::default_scene());
        self.message = Some(Message::Error(format!(
            "The shared link could not be opened: {problem}. Showing the default scene."
        )));
    }

    /// The scene as drawn (the Scene panel's, never a run's state), as a
    /// link (see [`crate::files::link`]).
    fn copy_link(&mut self, ctx: &egui::Context) {
        let result = self.scene_link().map(|fragment| {
            self.address.holds(self.scene.clone());
            io::share_link(ctx, &fragment)
        });
        self.message = Some(match result {
            Ok(text) => Message::Info(text),
            Err(e) => Message::Error(format!("No link: {e}")),
        });
    }

    /// Reads a study file for the Study tab (which then shows it); a bad
    /// file leaves the study read before and says why.
    fn open_study(&mut self, source: &str, text: &str) {
        match LoadedStudy::parse(source, text) {
            Ok(loaded) => {
                self.loaded_study = Some(loaded);
                self.study_file_setup.use_file = true;
                self.plot_tab = PlotTab::Study;
            }
            Err(e) => {
                self.message = Some(Message::Error(format!("Could not read the study {e}")));
            }
        }
    }

    /// Opens a scene file's text; a bad file leaves everything as it was.
    /// A study file (one with `axes`) opens in the Study tab instead.
    fn open_scene_text(&mut self, source: String, text: &str) {
        let is_study =
            serde_json::from_str::<serde_json::Value>(text).is_ok_and(|v| v.get("axes").is_some());
        if is_study {
            self.open_study(&source, text);
            return;
        }
        match cdca::Scene::from_json(text).map(cdca::Scene::into_file) {
            Ok(scene) => self.open_scene(source, scene),
            Err(e) => {
                self.message = Some(Message::Error(format!(
                    "Could not open {source}: {e}. The current scene is unchanged."
                )));
            }
        }
    }

    /// The CSV text File ▸ Export writes for a table (crack paths, growth
    /// history), the same as `cdca grow --csv` writes for the same run
    /// (`cdca::csv`), or a plot's *CSV…* button writes (the points the plot
    /// draws); `None` for the other exports and for an empty plot.
    pub fn table_csv(&self, what: Export) -> Option<String> {
        match what {
            Export::CrackPaths => Some(self.crack_paths_csv()),
            Export::History => Some(self.history_csv()),
            Export::StudyTable => self.file_study.as_ref().map(FileStudy::to_csv),
            Export::Plot {
                tab,
                index,
                format: PlotFormat::Csv,
            } => self.plot_figures(tab).get(index).map(Figure::to_csv),
            _ => None,
        }
    }

    /// The figures of a plot tab, as the plot panel draws them.
    fn plot_figures(&self, tab: PlotTab) -> Vec<Figure> {
        if tab == PlotTab::StudyMap {
            return self
                .file_study
                .as_ref()
                .map(|s| s.figures(self.study_file_setup.colour))
                .unwrap_or_default();
        }
        crate::plots::figures::figures(
            tab,
            self.runner.view(),
            self.race.as_ref().map(|r| r as &dyn Plotted),
            self.study.as_ref().map(|s| s as &dyn Plotted),
            [self.scene.specimen.width, self.scene.specimen.height],
        )
    }

    /// The crack paths: the simulation's cracks, or the scene's before a
    /// simulation has any.
    fn crack_paths_csv(&self) -> String {
        let cracks = if self.runner.view().cracks.is_empty() {
            let h = self.scene.element_size();
            self.scene.cracks.iter().map(|c| c.polyline(h)).collect()
        } else {
            self.runner.view().cracks.clone()
        };
        cdca::csv::crack_paths(&cracks)
    }

    fn history_csv(&self) -> String {
        cdca::csv::growth_history(&self.runner.view().history)
    }

    fn export(&mut self, ctx: &egui::Context, what: Export) {
        let stem = self.file_stem();
        let file = |name: &str, filter: (&'static str, &'static str), bytes: &[u8]| {
            Ok((name.to_owned(), filter, bytes.to_vec()))
        };
        let result: Result<FileToSave, String> = match what {
            Export::Scene => match self.scene_file() {
                Ok(json) => file(
                    &format!("{stem}.json"),
                    ("Scene (JSON)", "json"),
                    json.as_bytes(),
                ),
                Err(e) => Err(e),
            },
            Export::CrackPaths => file(
                &format!("{stem}_cracks.csv"),
                ("CSV", "csv"),
                self.crack_paths_csv().as_bytes(),
            ),
            Export::History => file(
                &format!("{stem}_history.csv"),
                ("CSV", "csv"),
                self.history_csv().as_bytes(),
            ),
            Export::Fields => {
                // the host writes them; saved when its answer comes
                // (`save_fields`)
                self.runner.request_fields();
                return;
            }
            Export::Race => match &self.race {
                None => Err("run Compare solvers before exporting the race".to_owned()),
                Some(race) => file(
                    &format!("{stem}_race.csv"),
                    ("CSV", "csv"),
                    race.to_csv().as_bytes(),
                ),
            },
            Export::Study => match &self.study {
                None => Err("run a study before exporting it".to_owned()),
                Some(study) => file(
                    &format!("{stem}_study.csv"),
                    ("CSV", "csv"),
                    study.to_csv().as_bytes(),
                ),
            },
            Export::StudyTable => match &self.file_study {
                None => Err("run a study file before exporting its table".to_owned()),
                Some(run) => {
                    let stem = run.source.trim_end_matches(".json").replace(' ', "_");
                    let first = if run.study.run == cdca::study::RunKind::FirstStep {
                        "_first_steps"
                    } else {
                        ""
                    };
                    file(
                        &format!("{stem}{first}.csv"),
                        ("CSV", "csv"),
                        run.to_csv().as_bytes(),
                    )
                }
            },
            Export::Plot { tab, index, format } => match self.plot_figures(tab).get(index) {
                None => Err("nothing to export: the plot is empty".to_owned()),
                Some(fig) => match format {
                    PlotFormat::Csv => file(
                        &format!("{stem}_{}.csv", fig.id),
                        ("CSV", "csv"),
                        fig.to_csv().as_bytes(),
                    ),
                    PlotFormat::Svg => file(
                        &format!("{stem}_{}.svg", fig.id),
                        ("SVG picture", "svg"),
                        fig.to_svg(900.0, 500.0).as_bytes(),
                    ),
                },
            },
            Export::CanvasPng => {
                self.request_canvas_png(ctx);
                return;
            }
        };
        match result {
            Ok((name, filter, bytes)) => {
                self.save_bytes(&name, filter, bytes, what == Export::Scene);
            }
            Err(e) => self.message = Some(Message::Error(e)),
        }
    }

    /// Saves the fields the host wrote for Export fields, once they come.
    pub(crate) fn save_fields(&mut self) {
        match self.runner.take_fields() {
            Some(Ok(vtu)) => {
                let name = format!("{}.vtu", self.file_stem());
                self.save_bytes(
                    &name,
                    ("VTK unstructured grid", "vtu"),
                    vtu.into_bytes(),
                    false,
                );
            }
            Some(Err(e)) => self.message = Some(Message::Error(e)),
            None => {}
        }
    }

    /// Saves `bytes` through the file dialog (named `name` at first), or,
    /// where no dialog can open, asks for a path above the canvas; the
    /// scene (`scene`) is then written as it stands when the path is used.
    pub(crate) fn save_bytes(
        &mut self,
        name: &str,
        filter: (&str, &str),
        bytes: Vec<u8>,
        scene: bool,
    ) {
        let picked = if self.options.file_dialogs {
            io::save_dialog(name, filter, &bytes, self.last_folder.as_deref())
        } else {
            Ok(io::Picked::NoDialog)
        };
        match picked {
            Ok(io::Picked::Chosen(path)) => self.saved(&path, scene),
            Ok(io::Picked::Cancelled) => {}
            Ok(io::Picked::NoDialog) => {
                let action = if scene {
                    PromptAction::SaveScene
                } else {
                    PromptAction::Save { bytes }
                };
                self.path_prompt = Some(PathPrompt {
                    action,
                    path: io::default_path(name, self.last_folder.as_deref()),
                });
            }
            Err(e) => self.message = Some(Message::Error(e)),
        }
    }

    /// Says where a file went (for the scene, after which growth step),
    /// and remembers its folder for the next Save and Open.
    fn saved(&mut self, path: &str, scene: bool) {
        let steps = self.runner.view().steps_done;
        let what = if scene && steps > 0 {
            format!(": the scene after growth step {steps}")
        } else {
            String::new()
        };
        self.message = Some(Message::Info(format!("Saved {path}{what}")));
        self.last_folder = std::path::Path::new(path)
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .map(std::path::Path::to_path_buf)
            .or_else(|| self.last_folder.take());
    }

    /// Uses the path typed where no dialog could open: writes the file or
    /// opens the scene. The field stays on error, to correct the path.
    fn use_typed_path(&mut self) {
        let Some(prompt) = self.path_prompt.take() else {
            return;
        };
        let path = prompt.path.trim().to_owned();
        let written = match &prompt.action {
            PromptAction::Save { bytes } => Some(io::write_file(&path, bytes).map(|p| (p, false))),
            // the last completed step when the path is used
            PromptAction::SaveScene => Some(
                self.scene_file()
                    .and_then(|json| io::write_file(&path, json.as_bytes()))
                    .map(|p| (p, true)),
            ),
            PromptAction::Open => None,
        };
        match written {
            Some(Ok((p, scene))) => self.saved(&p, scene),
            Some(Err(e)) => {
                self.message = Some(Message::Error(e));
                self.path_prompt = Some(prompt);
            }
            None => match io::read_text(std::path::Path::new(&path)) {
                Ok(file) => {
                    self.last_folder = std::path::Path::new(&path)
                        .parent()
                        .filter(|d| !d.as_os_str().is_empty())
                        .map(std::path::Path::to_path_buf);
                    self.open_scene_text(file.name, &file.text);
                }
                Err(e) => {
                    self.message = Some(Message::Error(e));
                    self.path_prompt = Some(prompt);
                }
            },
        }
    }

    /// The default file name: the scene's name, with `_edited` once the
    /// scene differs from the one opened (its name is still the old
    /// title's).
    pub(crate) fn file_stem(&self) -> String {
        let stem = file_stem(&self.scene);
        if self.is_edited() {
            format!("{stem}_edited")
        } else {
            stem
        }
    }
}

/// A file to save: its default name, its type (description, extension) and
/// its bytes.
type FileToSave = (String, (&'static str, &'static str), Vec<u8>);

/// A file name from the scene's name: lowercase letters, digits and `_`.
fn file_stem(scene: &SceneFile) -> String {
    let stem: String = scene
        .name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    let stem = stem.trim_matches('_').to_owned();
    if stem.is_empty() {
        "scene".to_owned()
    } else {
        stem
    }
}
