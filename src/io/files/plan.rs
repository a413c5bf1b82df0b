//! Triangle's command-line file rules, as library functions: which files a run reads (the input
//! name's extension and the switches decide: `.poly` with `p`, `.node` otherwise or when the
//! `.poly` has no vertices, `.ele` with `r`, `.area` with `r` and `a`), how they become the
//! engine's [`Input`] (numbering from the first vertex's number, indices checked, holes and
//! regions not carved with `r`), and which output files a run writes (`.node`, `.ele`, `.poly`,
//! `.edge`, `.v.node`/`.v.edge`, `.neigh`, `.off`, as the output switches say).

use std::io::{self, Write};

use super::read::{
    check_vertex_indices, read_area, read_ele, read_node, read_poly, AreaFile, EleFile, FileError,
    NodeFile, PolyFile,
};
use super::write::{
    write_edge, write_ele, write_neigh, write_node, write_off, write_poly, write_voronoi_edge,
    EleData, NodeData, PolyData, PolyVertices,
};
use crate::data::{Input, Output, VoronoiOutput};
use crate::options::Options;

/// The input files of one run, owned; the engine borrows them through [`InputFiles::input`].
pub struct InputFiles {
    pub vertices: NodeFile,
    /// The file the vertices came from.
    pub vertex_file: String,
    pub poly: Option<(PolyFile, String)>,
    pub ele: Option<(EleFile, String)>,
    pub area: Option<AreaFile>,
}

/// Reads the input files of `base` that `options` call for; `read(name)` gives a file's text.
pub fn read_inputs(
    base: &str,
    options: &Options,
    mut read: impl FnMut(&str) -> Result<String, FileError>,
) -> Result<InputFiles, FileError> {
    let mut poly = None;
    if options.pslg {
        let name = format!("{base}.poly");
        // Triangle reads the region section only for A or a-without-number, and not with r.
        let read_regions = (options.region_attributes || options.variable_area) && !options.refine;
        poly = Some((read_poly(&read(&name)?, &name, read_regions)?, name));
    }
    let (vertices, vertex_file) = match poly.as_mut() {
        Some((p, name)) if p.vertices.point_count() > 0 => {
            (std::mem::take(&mut p.vertices), name.clone())
        }
        _ => {
            let name = format!("{base}.node");
            (read_node(&read(&name)?, &name)?, name)
        }
    };
    let mut ele = None;
    let mut area = None;
    if options.refine {
        let name = format!("{base}.ele");
        let e = read_ele(&read(&name)?, &name)?;
        if options.variable_area {
            let area_name = format!("{base}.area");
            let a = read_area(&read(&area_name)?, &area_name)?;
            if a.areas.len() != e.triangle_count() {
                return Err(FileError {
                    file: area_name.clone(),
                    line: None,
                    message: format!(
                        "{name} and {area_name} disagree on the number of triangles ({} and {})",
                        e.triangle_count(),
                        a.areas.len()
                    ),
                });
            }
            area = Some(a);
        }
        ele = Some((e, name));
    }
    Ok(InputFiles {
        vertices,
        vertex_file,
        poly,
        ele,
        area,
    })
}

impl InputFiles {
    /// The numbering of every file: the first vertex's number when it is 0 or 1, otherwise
    /// `options`' (`z`).
    pub fn first_index(&self, options: &Options) -> i32 {
        match self.vertices.first_number {
            Some(0) => 0,
            Some(1) => 1,
            _ => options.first_index(),
        }
    }

    /// Checks what the engine cannot see in files (at least three vertices, segment and triangle
    /// indices in range, named by file and line), and gives the engine's input: the vertices,
    /// the segments, holes and regions of the `.poly` (holes and regions not with `r`, which
    /// carves nothing), the triangles of the `.ele` with the bounds of the `.area`.
    pub fn input(&self, options: &Options, first_index: i32) -> Result<Input<'_>, FileError> {
        let vertex_count = self.vertices.point_count();
        if vertex_count < 3 {
            return Err(FileError {
                file: self.vertex_file.clone(),
                line: None,
                message: "the input must have at least three vertices".into(),
            });
        }
        if let Some((poly, name)) = &self.poly {
            check_vertex_indices(
                name,
                "segment",
                &poly.segments,
                2,
                &poly.segment_lines,
                first_index,
                vertex_count,
            )?;
        }
        if let Some((ele, name)) = &self.ele {
            check_vertex_indices(
                name,
                "triangle",
                &ele.triangles,
                ele.corners,
                &ele.lines,
                first_index,
                vertex_count,
            )?;
        }
        let vertices = &self.vertices;
        let mut input = Input {
            points: &vertices.points,
            point_attributes: &vertices.attributes,
            point_attribute_count: vertices.attribute_count,
            point_markers: vertices.markers.as_deref(),
            ..Input::default()
        };
        if let Some((ele, _)) = &self.ele {
            input.triangles = &ele.triangles;
            input.corners = ele.corners;
            input.triangle_attributes = &ele.attributes;
            input.triangle_attribute_count = ele.attribute_count;
            input.triangle_areas = self.area.as_ref().map(|a| a.areas.as_slice());
        }
        if let Some((poly, _)) = &self.poly {
            input.segments = &poly.segments;
            input.segment_markers = poly.segment_markers.as_deref();
            if !options.refine {
                input.holes = &poly.holes;
                input.regions = &poly.regions;
            }
        }
        Ok(input)
    }

    /// The holes and regions of the `.poly` file (written back into the output `.poly`).
    pub fn holes_and_regions(&self) -> (&[f64], &[f64]) {
        self.poly
            .as_ref()
            .map_or((&[][..], &[][..]), |(p, _)| (&p.holes, &p.regions))
    }
}

/// Writes one file's contents (`Send + Sync`: the files of a run may be written in parallel).
pub type FileWriter<'a> = Box<dyn Fn(&mut dyn Write) -> io::Result<()> + Send + Sync + 'a>;

/// One output file: where it goes and how to write it.
pub struct PlannedFile<'a> {
    pub path: String,
    pub write: FileWriter<'a>,
}

/// What the engine must have returned for the outputs asked for.
fn required<'a, T>(array: &'a Option<Vec<T>>, what: &str) -> Result<&'a [T], FileError> {
    array.as_deref().ok_or_else(|| FileError {
        file: what.into(),
        line: None,
        message: "internal error: the engine returned none; please report this bug".into(),
    })
}

/// Which files a run writes, and how (Triangle's rules): `output_base.node` unless `N` (or `I`
/// with vertices from a `.node`, which it would overwrite), `.ele` unless `E`, `.poly` with `p`
/// or `c` unless `P` or `I`, `.edge` with `e`, `.v.node` and `.v.edge` with `v`, `.neigh` with
/// `n`, `.off` with `g`. Every file ends with `# Generated by <generated_by>`.
pub fn plan_outputs<'a>(
    options: &'a Options,
    output_base: &str,
    first_index: i32,
    generated_by: &'a str,
    inputs: &'a InputFiles,
    mesh: &'a Output,
    voronoi: &'a VoronoiOutput,
) -> Result<Vec<PlannedFile<'a>>, FileError> {
    let generated_by = Some(generated_by);
    let markers = !options.output.no_boundary_markers;
    let (holes, regions) = inputs.holes_and_regions();
    let vertices_from_node_file = inputs.vertex_file.ends_with(".node");
    let mut planned: Vec<PlannedFile<'a>> = Vec::new();
    let path = |extension: &str| format!("{output_base}.{extension}");

    let points = required(&mesh.points, "vertex list")?;
    let node = NodeData {
        points,
        attribute_count: mesh.point_attribute_count,
        attributes: mesh.point_attributes.as_deref().unwrap_or(&[]),
        markers: if markers {
            Some(required(&mesh.point_markers, "vertex marker list")?)
        } else {
            None
        },
    };
    let triangles = required(&mesh.triangles, "triangle list")?;
    let ele = EleData {
        corners: mesh.corners,
        triangles,
        attribute_count: mesh.triangle_attribute_count,
        attributes: mesh.triangle_attributes.as_deref().unwrap_or(&[]),
    };

    // -I writes no .node over the input .node (a .poly's own vertices are still written).
    let node_would_overwrite_input = options.output.no_iteration_numbers && vertices_from_node_file;
    if !options.output.no_node_output && !node_would_overwrite_input {
        planned.push(PlannedFile {
            path: path("node"),
            write: Box::new(move |mut w| write_node(&mut w, &node, first_index, generated_by)),
        });
    }
    if !options.output.no_element_output {
        planned.push(PlannedFile {
            path: path("ele"),
            write: Box::new(move |mut w| write_ele(&mut w, &ele, first_index, generated_by)),
        });
    }
    if (options.pslg || options.convex_hull)
        && !options.output.no_poly_output
        && !options.output.no_iteration_numbers
    {
        let data = PolyData {
            vertices: PolyVertices::InNodeFile {
                attribute_count: mesh.point_attribute_count,
                markers,
            },
            segments: required(&mesh.segments, "segment list")?,
            segment_markers: if markers {
                Some(required(&mesh.segment_markers, "segment marker list")?)
            } else {
                None
            },
            holes,
            regions,
        };
        planned.push(PlannedFile {
            path: path("poly"),
            write: Box::new(move |mut w| write_poly(&mut w, &data, first_index, generated_by)),
        });
    }
    if options.output.edges {
        let edges = required(&mesh.edges, "edge list")?;
        let edge_markers = if markers {
            Some(required(&mesh.edge_markers, "edge marker list")?)
        } else {
            None
        };
        planned.push(PlannedFile {
            path: path("edge"),
            write: Box::new(move |mut w| {
                write_edge(&mut w, edges, edge_markers, first_index, generated_by)
            }),
        });
    }
    if options.output.voronoi {
        let diagram = voronoi.diagram.as_ref().ok_or_else(|| FileError {
            file: "Voronoi diagram".into(),
            line: None,
            message: "internal error: the engine returned none; please report this bug".into(),
        })?;
        let voronoi_nodes = NodeData {
            points: &diagram.points,
            attribute_count: voronoi.point_attribute_count,
            attributes: &diagram.point_attributes,
            markers: None,
        };
        planned.push(PlannedFile {
            path: path("v.node"),
            write: Box::new(move |mut w| {
                write_node(&mut w, &voronoi_nodes, first_index, generated_by)
            }),
        });
        planned.push(PlannedFile {
            path: path("v.edge"),
            write: Box::new(move |mut w| {
                write_voronoi_edge(
                    &mut w,
                    &diagram.edges,
                    &diagram.norms,
                    first_index,
                    generated_by,
                )
            }),
        });
    }
    if options.output.neighbors {
        let neighbors = required(&mesh.neighbors, "neighbour list")?;
        planned.push(PlannedFile {
            path: path("neigh"),
            write: Box::new(move |mut w| write_neigh(&mut w, neighbors, first_index, generated_by)),
        });
    }
    if options.output.geomview {
        let edge_count = mesh.edge_count;
        planned.push(PlannedFile {
            path: path("off"),
            write: Box::new(move |mut w| {
                write_off(&mut w, points, &ele, edge_count, first_index, generated_by)
            }),
        });
    }
    Ok(planned)
}

/// Never one file written over another of the same run: the first path given twice, if any.
pub fn repeated_path<'p>(planned: &'p [PlannedFile<'_>]) -> Option<&'p str> {
    planned.iter().enumerate().find_map(|(i, file)| {
        planned[..i]
            .iter()
            .any(|other| std::path::Path::new(&other.path) == std::path::Path::new(&file.path))
            .then_some(file.path.as_str())
    })
}
