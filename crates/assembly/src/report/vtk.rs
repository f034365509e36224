//! VTK output for ParaView: one `.vtp` PolyData file per frame (each hose a polyline,
//! with point data `radius` for the Tube filter and `velocity`) and a `hoses.pvd`
//! collection that lists the frames with their times.

use pliant_core::{Model, State};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

pub struct VtkSeries {
    dir: PathBuf,
    frames: Vec<(f64, String)>,
}

impl VtkSeries {
    pub fn create(dir: &Path) -> std::io::Result<Self> {
        std::fs::create_dir_all(dir)?;
        Ok(VtkSeries {
            dir: dir.to_path_buf(),
            frames: Vec::new(),
        })
    }

    /// Writes one frame.
    pub fn frame(&mut self, model: &Model, state: &State) -> std::io::Result<()> {
        let name = format!("frame_{:05}.vtp", self.frames.len());
        let mut f = BufWriter::new(File::create(self.dir.join(&name))?);
        let n = model.node_count();
        writeln!(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>")?;
        writeln!(
            f,
            "<Piece NumberOfPoints=\"{n}\" NumberOfLines=\"{}\">",
            model.hoses.len()
        )?;
        writeln!(f, "<PointData Scalars=\"radius\">\n<DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">")?;
        for r in &model.radius {
            write!(f, "{r:.6e} ")?;
        }
        writeln!(f, "\n</DataArray>\n<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"ascii\">")?;
        for v in &state.v {
            write!(f, "{:.6e} {:.6e} {:.6e} ", v.x, v.y, v.z)?;
        }
        writeln!(f, "\n</DataArray>\n</PointData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">")?;
        for x in &state.x {
            write!(f, "{:.9e} {:.9e} {:.9e} ", x.x, x.y, x.z)?;
        }
        writeln!(f, "\n</DataArray>\n</Points>\n<Lines>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">")?;
        for h in &model.hoses {
            for i in h.nodes() {
                write!(f, "{i} ")?;
            }
        }
        writeln!(
            f,
            "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"
        )?;
        for h in &model.hoses {
            write!(f, "{} ", h.first_node + h.node_count)?;
        }
        writeln!(
            f,
            "\n</DataArray>\n</Lines>\n</Piece>\n</PolyData>\n</VTKFile>"
        )?;
        f.flush()?;
        self.frames.push((state.time, name));
        Ok(())
    }

    /// Writes the `hoses.pvd` collection.
    pub fn finish(&self) -> std::io::Result<()> {
        let mut f = BufWriter::new(File::create(self.dir.join("hoses.pvd"))?);
        writeln!(
            f,
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>"
        )?;
        for (t, name) in &self.frames {
            writeln!(f, "<DataSet timestep=\"{t:.6}\" file=\"{name}\"/>")?;
        }
        writeln!(f, "</Collection>\n</VTKFile>")?;
        f.flush()
    }
}
