//! An SVG picture of a mesh: triangles (shaded by their first attribute when they have one),
//! segments coloured by boundary marker, vertices, holes, region points and, when given, the
//! Voronoi diagram with its rays clipped to the frame. A modern stand-in for Triangle's X11
//! viewer `showme`, written by `triangle-rs --svg FILE`.

use std::io::{self, Write};

/// What to draw. Indices are in the mesh's numbering (from `first_index`); empty slices are
/// simply not drawn.
#[derive(Clone, Copy, Debug, Default)]
pub struct SvgScene<'a> {
    /// A caption (e.g. the command line); XML special characters are escaped.
    pub title: &'a str,
    pub first_index: i32,
    /// x, y per vertex.
    pub points: &'a [f64],
    /// `corners` vertex numbers per triangle (only the first three are drawn).
    pub triangles: &'a [i32],
    pub corners: usize,
    pub triangle_attributes: &'a [f64],
    pub triangle_attribute_count: usize,
    /// Two vertex numbers per segment and, optionally, their markers.
    pub segments: &'a [i32],
    pub segment_markers: Option<&'a [i32]>,
    /// x, y per hole.
    pub holes: &'a [f64],
    /// x, y, attribute, maximum area per region.
    pub regions: &'a [f64],
    pub voronoi: Option<SvgVoronoi<'a>>,
}

/// The Voronoi diagram as `VoronoiDiagram` holds it.
#[derive(Clone, Copy, Debug, Default)]
pub struct SvgVoronoi<'a> {
    pub points: &'a [f64],
    /// Two vertex numbers per edge; the second is -1 for a ray along `norms`.
    pub edges: &'a [i32],
    pub norms: &'a [f64],
}

/// Longest side of the drawing area, in pixels.
const DRAWING_SIZE: f64 = 800.0;
const MARGIN: f64 = 24.0;
/// Vertices are drawn as dots only up to this many (beyond, they would hide the triangles).
const MAX_VERTEX_DOTS: usize = 20_000;

/// Colour of a boundary marker: 0 (interior, no marker) grey, 1 to 10 a fixed palette, other
/// markers hues spread by the golden angle, so that nearby markers differ.
pub fn marker_colour(marker: i32) -> String {
    const PALETTE: [&str; 10] = [
        "#d62728", "#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf",
        "#bcbd22", "#393b79",
    ];
    match marker {
        0 => "#555555".to_string(),
        1..=10 => PALETTE[marker as usize - 1].to_string(),
        _ => format!(
            "hsl({:.0},70%,42%)",
            (marker as f64 * 137.508).rem_euclid(360.0)
        ),
    }
}

/// Maps mesh coordinates to pixels (y grows downwards in SVG).
struct Frame {
    min_x: f64,
    max_y: f64,
    scale: f64,
    width: f64,
    height: f64,
}

impl Frame {
    fn around(coordinates: impl Iterator<Item = (f64, f64)>) -> Frame {
        let (mut min_x, mut min_y, mut max_x, mut max_y) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
        for (x, y) in coordinates.filter(|(x, y)| x.is_finite() && y.is_finite()) {
            min_x = min_x.min(x);
            min_y = min_y.min(y);
            max_x = max_x.max(x);
            max_y = max_y.max(y);
        }
        if min_x > max_x {
            (min_x, min_y, max_x, max_y) = (0.0, 0.0, 1.0, 1.0);
        }
        let span = (max_x - min_x).max(max_y - min_y);
        let span = if span > 0.0 { span } else { 1.0 };
        let scale = DRAWING_SIZE / span;
        Frame {
            min_x,
            max_y,
            scale,
            width: (max_x - min_x) * scale + 2.0 * MARGIN,
            height: (max_y - min_y) * scale + 2.0 * MARGIN,
        }
    }

    fn x(&self, x: f64) -> f64 {
        (x - self.min_x) * self.scale + MARGIN
    }

    fn y(&self, y: f64) -> f64 {
        (self.max_y - y) * self.scale + MARGIN
    }
}

fn escape_xml(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            c if (c as u32) < 0x20 && c != '\t' && c != '\n' => escaped.push(' '),
            c => escaped.push(c),
        }
    }
    escaped
}

/// A pastel colour for `t` in [0, 1] (blue to orange), for triangle attributes.
fn pastel(t: f64) -> String {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let hue = 210.0 - 180.0 * t;
    format!("hsl({hue:.0},70%,85%)")
}

/// Writes the picture of `scene` as a standalone SVG document.
pub fn write_svg(w: &mut impl Write, scene: &SvgScene<'_>) -> io::Result<()> {
    let point = |v: i32| -> Option<(f64, f64)> {
        let i = usize::try_from(v as i64 - scene.first_index as i64).ok()?;
        Some((*scene.points.get(2 * i)?, *scene.points.get(2 * i + 1)?))
    };
    let frame = Frame::around(
        scene
            .points
            .chunks_exact(2)
            .chain(scene.holes.chunks_exact(2))
            .chain(scene.regions.chunks_exact(4))
            .map(|p| (p[0], p[1])),
    );
    let legend_height = 40.0;
    let (width, height) = (frame.width, frame.height + legend_height);

    writeln!(w, r#"<?xml version="1.0" encoding="UTF-8"?>"#)?;
    writeln!(
        w,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.2} {height:.2}">"#
    )?;
    writeln!(w, "<title>{}</title>", escape_xml(scene.title))?;
    writeln!(
        w,
        r#"<defs><clipPath id="frame"><rect x="0" y="0" width="{:.2}" height="{:.2}"/></clipPath></defs>"#,
        frame.width, frame.height
    )?;
    writeln!(
        w,
        r#"<rect x="0" y="0" width="{width:.2}" height="{height:.2}" fill="white"/>"#
    )?;

    // Triangles, shaded by their first attribute if they have one.
    let corners = scene.corners.max(3);
    let triangle_count = if scene.corners >= 3 {
        scene.triangles.len() / scene.corners
    } else {
        0
    };
    let first_attribute = |t: usize| {
        (scene.triangle_attribute_count > 0)
            .then(|| {
                scene
                    .triangle_attributes
                    .get(t * scene.triangle_attribute_count)
                    .copied()
            })
            .flatten()
    };
    let (low, high) = (0..triangle_count)
        .filter_map(first_attribute)
        .fold((f64::MAX, f64::MIN), |(lo, hi), a| (lo.min(a), hi.max(a)));
    writeln!(
        w,
        r##"<g id="triangles" fill="#eef4fb" stroke="#7f8c9a" stroke-width="0.6" stroke-linejoin="round">"##
    )?;
    for t in 0..triangle_count {
        let corner_points: Vec<(f64, f64)> = scene.triangles[t * corners..t * corners + 3]
            .iter()
            .filter_map(|&v| point(v))
            .collect();
        if corner_points.len() < 3 {
            continue;
        }
        write!(w, r#"<polygon points=""#)?;
        for (k, (x, y)) in corner_points.iter().enumerate() {
            let separator = if k > 0 { " " } else { "" };
            write!(w, "{separator}{:.2},{:.2}", frame.x(*x), frame.y(*y))?;
        }
        match first_attribute(t) {
            Some(a) => {
                let t = if high > low {
                    (a - low) / (high - low)
                } else {
                    0.0
                };
                writeln!(w, r#"" fill="{}"/>"#, pastel(t))?;
            }
            None => writeln!(w, r#""/>"#)?,
        }
    }
    writeln!(w, "</g>")?;

    // The Voronoi diagram, clipped to the frame: rays are drawn long enough to leave it.
    if let Some(voronoi) = scene.voronoi {
        let ray_length = 4.0 * (frame.width + frame.height) / frame.scale;
        let vertex = |v: i32| -> Option<(f64, f64)> {
            let i = usize::try_from(v as i64 - scene.first_index as i64).ok()?;
            Some((*voronoi.points.get(2 * i)?, *voronoi.points.get(2 * i + 1)?))
        };
        writeln!(
            w,
            r##"<g id="voronoi" clip-path="url(#frame)" stroke="#2e8b57" stroke-width="0.8" fill="none">"##
        )?;
        for (e, pair) in voronoi.edges.chunks_exact(2).enumerate() {
            let Some(start) = vertex(pair[0]) else {
                continue;
            };
            let end = if pair[1] == -1 {
                let (dx, dy) = (
                    voronoi.norms.get(2 * e).copied(),
                    voronoi.norms.get(2 * e + 1).copied(),
                );
                let (dx, dy) = (dx.unwrap_or(0.0), dy.unwrap_or(0.0));
                let length = dx.hypot(dy);
                if length.is_nan() || length <= 0.0 {
                    continue;
                }
                (
                    start.0 + dx / length * ray_length,
                    start.1 + dy / length * ray_length,
                )
            } else {
                let Some(end) = vertex(pair[1]) else { continue };
                end
            };
            if ![start.0, start.1, end.0, end.1]
                .iter()
                .all(|c| c.is_finite())
            {
                continue;
            }
            writeln!(
                w,
                r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}"/>"#,
                frame.x(start.0),
                frame.y(start.1),
                frame.x(end.0),
                frame.y(end.1)
            )?;
        }
        for p in voronoi.points.chunks_exact(2) {
            writeln!(
                w,
                r##"<circle cx="{:.2}" cy="{:.2}" r="1.6" fill="#2e8b57"/>"##,
                frame.x(p[0]),
                frame.y(p[1])
            )?;
        }
        writeln!(w, "</g>")?;
    }

    // Segments, coloured by marker.
    let mut markers_seen: Vec<i32> = Vec::new();
    writeln!(
        w,
        r#"<g id="segments" stroke-width="2.5" stroke-linecap="round">"#
    )?;
    for (s, pair) in scene.segments.chunks_exact(2).enumerate() {
        let (Some(a), Some(b)) = (point(pair[0]), point(pair[1])) else {
            continue;
        };
        let marker = scene
            .segment_markers
            .and_then(|m| m.get(s).copied())
            .unwrap_or(0);
        if !markers_seen.contains(&marker) {
            markers_seen.push(marker);
        }
        writeln!(
            w,
            r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="{}"/>"#,
            frame.x(a.0),
            frame.y(a.1),
            frame.x(b.0),
            frame.y(b.1),
            marker_colour(marker)
        )?;
    }
    writeln!(w, "</g>")?;

    if scene.points.len() / 2 <= MAX_VERTEX_DOTS {
        writeln!(w, r##"<g id="vertices" fill="#222222">"##)?;
        for p in scene.points.chunks_exact(2) {
            writeln!(
                w,
                r#"<circle cx="{:.2}" cy="{:.2}" r="1.8"/>"#,
                frame.x(p[0]),
                frame.y(p[1])
            )?;
        }
        writeln!(w, "</g>")?;
    }

    writeln!(
        w,
        r##"<g id="holes" stroke="#cc0000" stroke-width="2" fill="none">"##
    )?;
    for h in scene.holes.chunks_exact(2) {
        let (x, y) = (frame.x(h[0]), frame.y(h[1]));
        writeln!(
            w,
            r#"<path d="M{:.2},{:.2} L{:.2},{:.2} M{:.2},{:.2} L{:.2},{:.2}"/>"#,
            x - 5.0,
            y - 5.0,
            x + 5.0,
            y + 5.0,
            x - 5.0,
            y + 5.0,
            x + 5.0,
            y - 5.0
        )?;
    }
    writeln!(w, "</g>")?;

    writeln!(
        w,
        r##"<g id="regions" font-family="sans-serif" font-size="11" fill="#1f3b99">"##
    )?;
    for r in scene.regions.chunks_exact(4) {
        let (x, y) = (frame.x(r[0]), frame.y(r[1]));
        writeln!(w, r#"<circle cx="{x:.2}" cy="{y:.2}" r="4"/>"#)?;
        writeln!(
            w,
            r#"<text x="{:.2}" y="{:.2}">{}</text>"#,
            x + 6.0,
            y - 4.0,
            escape_xml(&format!(
                "attr {} area {}",
                super::files::g17(r[2]),
                super::files::g17(r[3])
            ))
        )?;
    }
    writeln!(w, "</g>")?;

    // Legend: counts, the caption and a swatch per segment marker.
    markers_seen.sort_unstable();
    let top = frame.height + 14.0;
    writeln!(
        w,
        r##"<g id="legend" font-family="sans-serif" font-size="12" fill="#222222">"##
    )?;
    writeln!(
        w,
        r#"<text x="{MARGIN:.2}" y="{top:.2}">{} vertices, {triangle_count} triangles, {} segments{}</text>"#,
        scene.points.len() / 2,
        scene.segments.len() / 2,
        escape_xml(&if scene.title.is_empty() {
            String::new()
        } else {
            format!(" — {}", scene.title)
        })
    )?;
    let mut x = MARGIN;
    for marker in markers_seen.iter().take(24) {
        writeln!(
            w,
            r#"<rect x="{x:.2}" y="{:.2}" width="14" height="4" fill="{}"/><text x="{:.2}" y="{:.2}">marker {marker}</text>"#,
            top + 10.0,
            marker_colour(*marker),
            x + 18.0,
            top + 16.0
        )?;
        x += 90.0;
    }
    writeln!(w, "</g>")?;
    writeln!(w, "</svg>")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_every_triangle_segment_and_the_voronoi_diagram() {
        let points = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
        let scene = SvgScene {
            title: "a <test> & more",
            first_index: 1,
            points: &points,
            triangles: &[1, 2, 3, 1, 3, 4],
            corners: 3,
            triangle_attributes: &[1.0, 2.0],
            triangle_attribute_count: 1,
            segments: &[1, 2, 2, 3, 3, 4, 4, 1],
            segment_markers: Some(&[1, 1, 2, 0]),
            holes: &[0.5, 0.5],
            regions: &[0.2, 0.8, 3.0, 0.1],
            voronoi: Some(SvgVoronoi {
                points: &[0.5, 0.5, 0.5, 0.5],
                edges: &[1, 2, 1, -1],
                norms: &[0.0, 0.0, 0.0, -1.0],
            }),
        };
        let mut out = Vec::new();
        write_svg(&mut out, &scene).unwrap();
        let svg = String::from_utf8(out).unwrap();
        assert!(svg.starts_with("<?xml"));
        assert!(svg.trim_end().ends_with("</svg>"));
        assert_eq!(svg.matches("<polygon").count(), 2);
        assert_eq!(svg.matches("<line").count(), 4 + 2);
        assert!(svg.contains("a &lt;test&gt; &amp; more"));
        assert!(svg.contains(&marker_colour(2)));
        assert_ne!(marker_colour(1), marker_colour(11));
        assert!(svg.contains("hsl("));
        // Every element opened is closed (a cheap well-formedness check).
        assert_eq!(svg.matches("<g ").count(), svg.matches("</g>").count());
    }

    #[test]
    fn degenerate_extent_does_not_divide_by_zero() {
        let scene = SvgScene {
            points: &[2.0, 2.0, 2.0, 2.0, 2.0, 2.0],
            first_index: 0,
            ..SvgScene::default()
        };
        let mut out = Vec::new();
        write_svg(&mut out, &scene).unwrap();
        let svg = String::from_utf8(out).unwrap();
        assert!(!svg.contains("NaN") && !svg.contains("inf"));
    }
}
