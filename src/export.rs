//! File contents the workbench writes: crack paths and growth history as
//! CSV, the fields as a VTK unstructured grid (.vtu, for ParaView), the
//! canvas as PNG. Pure functions to text or bytes; `io` does the writing.

use std::fmt::Write as _;

use cdca::fracture::rock::RockStrength;
use cdca::report::{GrowthStepReport, Mode};
use cdca::scene::SceneFile;

use crate::field::von_mises;

/// `crack,vertex,x_m,y_m`, one row per polyline vertex.
pub fn crack_paths_csv(cracks: &[Vec<[f64; 2]>]) -> String {
    let mut out = String::from("crack,vertex,x_m,y_m\n");
    for (i, c) in cracks.iter().enumerate() {
        for (k, p) in c.iter().enumerate() {
            let _ = writeln!(out, "{i},{k},{:e},{:e}", p[0], p[1]);
        }
    }
    out
}

fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Tension => "tension",
        Mode::Shear => "shear",
        Mode::None => "none",
    }
}

/// One row per growth step and free tip: SIFs, the criterion's decision,
/// whether the tip grew, contact counts, solver effort and the intact
/// rock's utilisation of its strength.
pub fn history_csv(history: &[GrowthStepReport]) -> String {
    let mut out = String::from(
        "step,load_factor,crack,tip,x_m,y_m,k1_pa_sqrt_m,k2_pa_sqrt_m,t_stress_pa,mode,angle_deg,grew,open,stick,slip,solver_iterations,seconds,converged,intact_rock_utilisation\n",
    );
    for s in history {
        let tail = format!(
            "{},{},{},{},{:e},{},{}",
            s.contact.open,
            s.contact.stick,
            s.contact.slip,
            s.solver_iterations,
            s.seconds,
            s.converged,
            s.intact_rock
                .map(|r| r.utilisation.to_string())
                .unwrap_or_default()
        );
        if s.tips.is_empty() {
            let _ = writeln!(out, "{},{},,,,,,,,,,,{tail}", s.step, s.load_factor);
        }
        for t in &s.tips {
            let grew = s.grown.iter().any(|g| g.crack == t.crack && g.tip == t.tip);
            let _ = writeln!(
                out,
                "{},{},{},{},{:e},{:e},{:e},{:e},{:e},{},{},{},{tail}",
                s.step,
                s.load_factor,
                t.crack,
                t.tip,
                t.x,
                t.y,
                t.k1,
                t.k2,
                t.t_stress,
                mode_name(t.criterion.mode),
                t.criterion.angle_deg,
                u8::from(grew),
            );
        }
    }
    out
}

/// The Q4 mesh with point data `displacement` (m) and cell data stresses
/// (Pa) and the rock's strength used (–, see `RockStrength::utilisation`)
/// sampled at cell centres; values the solver cannot give are 0 (the
/// strength used too, for a rock without cohesion).
pub fn fields_vtu(
    scene: &SceneFile,
    displacement_at: impl Fn([f64; 2]) -> Option<[f64; 2]>,
    stress_at: impl Fn([f64; 2]) -> Option<[f64; 3]>,
) -> String {
    let (nx, ny) = (scene.mesh.nx, scene.mesh.ny);
    let (dx, dy) = (
        scene.specimen.width / nx as f64,
        scene.specimen.height / ny as f64,
    );
    let node = |i: usize, j: usize| [i as f64 * dx, j as f64 * dy];
    let n_points = (nx + 1) * (ny + 1);
    let n_cells = nx * ny;
    let mut points = String::new();
    let mut disp = String::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let p = node(i, j);
            let u = displacement_at(p).unwrap_or([0.0; 2]);
            let _ = writeln!(points, "{:e} {:e} 0", p[0], p[1]);
            let _ = writeln!(disp, "{:e} {:e} 0", u[0], u[1]);
        }
    }
    let names = [
        "sigma_xx",
        "sigma_yy",
        "tau_xy",
        "sigma_1",
        "sigma_3",
        "von_mises",
        "rock_strength_used",
    ];
    let rock = RockStrength::of_material(&scene.material);
    let used = |s: [f64; 3]| rock.map_or(0.0, |r| r.utilisation(s));
    let mut cell_data = vec![String::new(); names.len()];
    let mut connectivity = String::new();
    let mut offsets = String::new();
    for j in 0..ny {
        for i in 0..nx {
            let s = stress_at([(i as f64 + 0.5) * dx, (j as f64 + 0.5) * dy]).unwrap_or([0.0; 3]);
            let (c, r) = (0.5 * (s[0] + s[1]), (0.5 * (s[0] - s[1])).hypot(s[2]));
            let vm = von_mises(s, scene.material.plane, scene.material.poisson);
            for (out, v) in cell_data
                .iter_mut()
                .zip([s[0], s[1], s[2], c + r, c - r, vm, used(s)])
            {
                let _ = writeln!(out, "{v:e}");
            }
            let n0 = j * (nx + 1) + i;
            let _ = writeln!(
                connectivity,
                "{} {} {} {}",
                n0,
                n0 + 1,
                n0 + nx + 2,
                n0 + nx + 1
            );
            let _ = writeln!(offsets, "{}", 4 * (j * nx + i + 1));
        }
    }
    let mut out = String::new();
    let _ = write!(
        out,
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"{n_points}\" NumberOfCells=\"{n_cells}\">\n<PointData Vectors=\"displacement\">\n<DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" format=\"ascii\">\n{disp}</DataArray>\n</PointData>\n<CellData Scalars=\"von_mises\">\n"
    );
    for (name, data) in names.iter().zip(&cell_data) {
        let _ = write!(
            out,
            "<DataArray type=\"Float64\" Name=\"{name}\" format=\"ascii\">\n{data}</DataArray>\n"
        );
    }
    let types = "9\n".repeat(n_cells);
    let _ = write!(
        out,
        "</CellData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n{points}</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n{connectivity}</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n{offsets}</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n{types}</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n"
    );
    out
}

/// An RGBA PNG of `image`.
pub fn png_bytes(image: &egui::ColorImage) -> Result<Vec<u8>, String> {
    let [w, h] = image.size;
    let mut rgba = Vec::with_capacity(4 * w * h);
    for c in &image.pixels {
        rgba.extend_from_slice(&c.to_srgba_unmultiplied());
    }
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, w as u32, h as u32);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
    writer.write_image_data(&rgba).map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::default_scene;
    use cdca::report::{ContactCounts, GrownTip, TipReport};

    #[test]
    fn crack_paths_have_one_row_per_vertex() {
        let csv = crack_paths_csv(&[
            vec![[0.1, 0.1], [0.2, 0.2]],
            vec![[0.0, 0.5], [0.1, 0.5], [0.2, 0.6]],
        ]);
        assert_eq!(csv.lines().count(), 1 + 5);
        assert!(csv.lines().nth(3).is_some_and(|l| l.starts_with("1,0,")));
    }

    #[test]
    fn history_marks_the_tips_that_grew() {
        let tip = |tip| TipReport {
            crack: 0,
            tip,
            ..TipReport::default()
        };
        let step = GrowthStepReport {
            step: 3,
            load_factor: 0.5,
            grown: vec![GrownTip {
                crack: 0,
                tip: 1,
                ..GrownTip::default()
            }],
            contact: ContactCounts {
                open: 1,
                stick: 2,
                slip: 3,
                ..ContactCounts::default()
            },
            tips: vec![tip(0), tip(1)],
            ..GrowthStepReport::default()
        };
        let csv = history_csv(&[step]);
        let rows: Vec<Vec<&str>> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').collect())
            .collect();
        assert_eq!(rows.len(), 2);
        assert_eq!((rows[0][11], rows[1][11]), ("0", "1"));
        let header_columns = csv.lines().next().map_or(0, |h| h.split(',').count());
        assert!(rows.iter().all(|r| r.len() == header_columns));
    }

    #[test]
    fn vtu_counts_match_the_mesh() {
        let mut scene = default_scene();
        scene.mesh.nx = 3;
        scene.mesh.ny = 2;
        let vtu = fields_vtu(&scene, |p| Some([p[0], 0.0]), |_| Some([-1.0, -2.0, 0.0]));
        assert!(vtu.contains("NumberOfPoints=\"12\" NumberOfCells=\"6\""));
        assert_eq!(vtu.matches("Name=").count(), 1 + 7 + 3);
        // the last cell's connectivity is 6 7 11 10
        assert!(vtu.contains("6 7 11 10\n"));
        assert!(vtu.trim_end().ends_with("</VTKFile>"));
    }

    #[test]
    fn png_starts_with_the_signature() {
        let image = egui::ColorImage::new([3, 2], vec![egui::Color32::RED; 6]);
        let bytes = png_bytes(&image).unwrap_or_default();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    }
}
