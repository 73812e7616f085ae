//! File contents the workbench writes besides the CSV tables (those come
//! from `cdca::csv`, shared with the CLI): the fields as a VTK unstructured
//! grid (.vtu, for ParaView), the canvas as PNG. Pure functions to text or
//! bytes; `io` does the writing.

use std::fmt::Write as _;

use cdca::fracture::rock::RockStrength;
use cdca::scene::SceneFile;

use crate::results::field::von_mises;

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
    use crate::files::scenes::default_scene;

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
