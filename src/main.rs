//! The CDCA workbench: native window, or the browser (WebAssembly).

#![cfg_attr(not(debug_assertions), windows_subsystem = "windows")]

/// How to start the workbench from a shell.
#[cfg(not(target_arch = "wasm32"))]
const USAGE: &str = "usage: cdca-workbench [SCENE.json | --link LINK] [--run relax|grow|compare]
                     [--study PATH FROM TO COUNT] [--study-file STUDY.json]
                     [--size WIDTHxHEIGHT] [--plot TAB] [--time-run]

Opens SCENE.json, or the scene a shared link carries (a web address or its
#scene=… fragment, from File > Copy link to this scene; default: the last
scene) and, with --run, starts the
relaxation (relax), the growth run (grow) or the solver race (compare)
after the first solve; with --study, a parameter study of the scene field
PATH (e.g. cracks.0.friction) over COUNT values from FROM to TO, in the
Study tab's units (MPa, mm, °, or none); with --study-file, the first
steps of every point of a study file (docs/studies.md) in the Study tab.
--size sets the window's size in points (default 1400x900; e.g. 1024x640
for a projector, 390x844 for a phone's). --plot shows the plot TAB
(residual, residual-time, k, angles, load, race or study) whatever runs,
for screenshots. --time-run: when the --run
ends, print its wall time and frame times and close the window.";

/// What the command line asks for.
#[cfg(not(target_arch = "wasm32"))]
struct Launch {
    /// (file name, scene) to open.
    scene: Option<(String, cdca::scene::SceneFile)>,
    run: Option<cdca_workbench::StartRun>,
    /// The window's inner size, points.
    size: [f32; 2],
    /// `--time-run`.
    time_run: bool,
    /// `--plot`: the plot tab shown whatever runs.
    plot: Option<cdca_workbench::PlotTab>,
}

/// Parses the command line (without the program name). `Ok(None)`: help
/// was asked for.
#[cfg(not(target_arch = "wasm32"))]
fn parse_args(mut args: impl Iterator<Item = String>) -> Result<Option<Launch>, String> {
    use cdca_workbench::StartRun;
    let mut launch = Launch {
        scene: None,
        run: None,
        size: [1400.0, 900.0],
        time_run: false,
        plot: None,
    };
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "-h" | "--help" => return Ok(None),
            "--run" => {
                let what = args.next().ok_or("--run needs relax, grow or compare")?;
                launch.run = Some(match what.as_str() {
                    "relax" => StartRun::Relax,
                    "grow" => StartRun::Grow,
                    "compare" => StartRun::Compare,
                    other => {
                        return Err(format!("--run {other}: expected relax, grow or compare"));
                    }
                });
            }
            "--time-run" => launch.time_run = true,
            "--plot" => {
                let name = args.next().ok_or("--plot needs a tab")?;
                launch.plot = Some(
                    cdca_workbench::PlotTab::from_arg(&name)
                        .ok_or(format!("--plot {name}: expected residual, residual-time, k, angles, load, race or study"))?,
                );
            }
            "--link" => {
                let link = args.next().ok_or("--link needs a link (…#scene=…)")?;
                let scene = match cdca_workbench::files::link::from_link(&link) {
                    Some(Ok(scene)) => scene,
                    Some(Err(e)) => return Err(format!("--link: {e}")),
                    None => return Err("--link: the link carries no scene (#scene=…)".to_owned()),
                };
                if launch.scene.is_some() {
                    return Err("--link: only one scene can be opened".to_owned());
                }
                launch.scene = Some(("shared link".to_owned(), scene));
            }
            "--study" => {
                let mut next = |what: &str| {
                    args.next()
                        .ok_or(format!("--study needs PATH FROM TO COUNT (missing {what})"))
                };
                let path = next("PATH")?;
                let number = |what: &str, text: String| {
                    text.parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or(format!("--study {what}: `{text}` is not a number"))
                };
                let from = number("FROM", next("FROM")?)?;
                let to = number("TO", next("TO")?)?;
                let count_text = next("COUNT")?;
                let count = count_text
                    .parse::<usize>()
                    .ok()
                    .filter(|&n| (1..=200).contains(&n))
                    .ok_or(format!(
                        "--study COUNT: `{count_text}` is not a count from 1 to 200"
                    ))?;
                launch.run = Some(StartRun::Study(cdca_workbench::study::StudySetup {
                    path,
                    from,
                    to,
                    count,
                }));
            }
            "--study-file" => {
                let path = args.next().ok_or("--study-file needs STUDY.json")?;
                let text = std::fs::read_to_string(&path)
                    .map_err(|e| format!("cannot read {path}: {e}"))?;
                let source = std::path::Path::new(&path)
                    .file_name()
                    .map_or_else(|| path.clone(), |n| n.to_string_lossy().into_owned());
                launch.run = Some(StartRun::StudyFile { source, text });
            }
            "--size" => {
                let text = args.next().ok_or("--size needs WIDTHxHEIGHT")?;
                launch.size = text
                    .split_once('x')
                    .and_then(|(w, h)| Some([w.parse::<f32>().ok()?, h.parse::<f32>().ok()?]))
                    .filter(|s| s.iter().all(|v| (200.0..=10_000.0).contains(v)))
                    .ok_or(format!("--size {text}: expected e.g. 1024x640"))?;
            }
            flag if flag.starts_with('-') => return Err(format!("unknown option {flag}")),
            path => {
                if launch.scene.is_some() {
                    return Err(format!("{path}: only one scene file can be opened"));
                }
                let text = std::fs::read_to_string(path)
                    .map_err(|e| format!("cannot read {path}: {e}"))?;
                let scene = cdca::Scene::from_json(&text)
                    .map(cdca::Scene::into_file)
                    .map_err(|e| format!("{path} is not a valid scene: {e}"))?;
                let name = std::path::Path::new(path)
                    .file_name()
                    .map_or_else(|| path.to_owned(), |n| n.to_string_lossy().into_owned());
                launch.scene = Some((name, scene));
            }
        }
    }
    Ok(Some(launch))
}

#[cfg(not(target_arch = "wasm32"))]
fn main() -> eframe::Result {
    if std::env::var_os("CDCA_STARTUP_REPORT").is_some() {
        let _ = cdca_workbench::app::STARTUP_REPORT.set(web_time::Instant::now());
    }
    let launch = match parse_args(std::env::args().skip(1)) {
        Ok(Some(launch)) => launch,
        Ok(None) => {
            println!("{USAGE}");
            return Ok(());
        }
        Err(e) => {
            eprintln!("cdca-workbench: {e}\n\n{USAGE}");
            std::process::exit(2);
        }
    };
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("CDCA workbench")
            .with_inner_size(launch.size)
            // a phone's width: the layout hides the side panels below 800
            .with_min_inner_size([320.0, 400.0]),
        ..Default::default()
    };
    eframe::run_native(
        "cdca-workbench",
        options,
        Box::new(move |cc| {
            Ok(Box::new(cdca_workbench::WorkbenchApp::launch(
                cc,
                launch.scene,
                launch.run,
                launch.time_run,
                launch.plot,
                true,
            )))
        }),
    )
}

/// The web build: logs to the browser console, starts the app on the
/// page's `<canvas id="cdca_canvas">`, and replaces the page's loading
/// note with a visible message if the start fails or the app panics
/// (instead of leaving a blank page).
#[cfg(target_arch = "wasm32")]
fn main() {
    use eframe::wasm_bindgen::JsCast as _;

    if eframe::WebLogger::init(log::LevelFilter::Info).is_err() {
        web_sys::console::warn_1(&"no console logger".into());
    }
    // the same module in the solver's Web Worker (`worker.js`): no window,
    // no app; the worker serves the page's requests
    if web_sys::window().is_none() {
        std::panic::set_hook(Box::new(|info| {
            log::error!("the solver's worker stopped: {info}")
        }));
        cdca_workbench::serve_worker();
        return;
    }
    let runner = eframe::WebRunner::new();
    // After `WebRunner::new`, so eframe's hook (which logs to the console)
    // still runs first.
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        previous_hook(info);
        show_status(&format!("The workbench stopped: {info}"), true);
    }));
    wasm_bindgen_futures::spawn_local(async move {
        let Some(canvas) = web_sys::window()
            .and_then(|w| w.document())
            .and_then(|d| d.get_element_by_id("cdca_canvas"))
            .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
        else {
            show_status("The page has no <canvas id=\"cdca_canvas\">.", true);
            return;
        };
        let started = runner
            .start(
                canvas,
                eframe::WebOptions {
                    dithering: false,
                    ..eframe::WebOptions::default()
                },
                Box::new(|cc| Ok(Box::new(cdca_workbench::app::web::WebApp::new(cc)))),
            )
            .await;
        match started {
            Ok(()) => show_status("", false),
            Err(e) => {
                log::error!("failed to start: {e:?}");
                show_status(
                    &format!(
                        "The workbench could not start: {}. It needs WebGL 2; see the browser console for details.",
                        e.as_string().unwrap_or_else(|| format!("{e:?}"))
                    ),
                    true,
                );
            }
        }
    });
}

/// Shows `text` in the page's `#cdca_status` element (as an error when
/// `error`), or hides it when `text` is empty.
#[cfg(target_arch = "wasm32")]
fn show_status(text: &str, error: bool) {
    let Some(status) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id("cdca_status"))
    else {
        return;
    };
    status.set_text_content(Some(text));
    let class = match (text.is_empty(), error) {
        (true, _) => "hidden",
        (false, true) => "error",
        (false, false) => "",
    };
    let _ = status.set_attribute("class", class);
}
