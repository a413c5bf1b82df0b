use super::records::{parse_c_integer, parse_c_real};
use super::*;

#[test]
fn c_number_prefixes() {
    assert_eq!(parse_c_integer("12"), Some(Ok(12)));
    assert_eq!(parse_c_integer("-3"), Some(Ok(-3)));
    assert_eq!(parse_c_integer("0x10"), Some(Ok(16)));
    assert_eq!(parse_c_integer("010"), Some(Ok(8)));
    assert_eq!(parse_c_integer("3.0"), Some(Ok(3)));
    assert_eq!(parse_c_integer("0"), Some(Ok(0)));
    assert_eq!(parse_c_integer("-"), None);
    assert_eq!(parse_c_integer("99999999999999999999"), Some(Err(())));
    assert_eq!(parse_c_real("0.418893E+02"), Some(41.8893));
    assert_eq!(parse_c_real("1."), Some(1.0));
    assert_eq!(parse_c_real("1.e2"), Some(100.0));
    assert_eq!(parse_c_real(".5"), Some(0.5));
    assert_eq!(parse_c_real("-2e-3x"), Some(-0.002));
    assert_eq!(parse_c_real("+7"), Some(7.0));
    assert_eq!(parse_c_real("3e"), Some(3.0));
    assert_eq!(parse_c_real("."), None);
    assert_eq!(parse_c_real("-"), None);
}

#[test]
fn node_with_comments_blank_lines_and_defaults() {
    let text = "# a comment\n\n  4 2 1 1 # header\r\n\
                1 0 0 10 5\n\
                2\t1.5e0 0   # no attribute, no marker\n\
                # between\n\
                3 1 1 30 0 extra words\n\
                4 0 1.0E+00 40 -2\n";
    let node = read_node(text, "x.node").unwrap();
    assert_eq!(node.first_number, Some(1));
    assert_eq!(node.points, vec![0.0, 0.0, 1.5, 0.0, 1.0, 1.0, 0.0, 1.0]);
    assert_eq!(node.attributes, vec![10.0, 0.0, 30.0, 40.0]);
    assert_eq!(node.markers, Some(vec![5, 0, 0, -2]));
}

#[test]
fn node_header_defaults_and_zero_base() {
    let node = read_node("3\n0 0 0\n1 1 0\n2 0 1\n", "z.node").unwrap();
    assert_eq!(node.first_number, Some(0));
    assert_eq!(node.attribute_count, 0);
    assert_eq!(node.markers, None);
    assert_eq!(node.point_count(), 3);
}

#[test]
fn node_errors_name_file_and_line() {
    let e = read_node("3 2 0 0\n1 0 0\n2 1\n3 0 1\n", "bad.node").unwrap_err();
    assert_eq!(e.line, Some(3));
    assert!(e.message.contains("y coordinate of vertex 2"), "{e}");
    assert!(e.to_string().starts_with("bad.node, line 3: "), "{e}");

    let e = read_node("4 2 0 0\n1 0 0\n2 1 0\n3 0 1\n", "short.node").unwrap_err();
    assert!(e.message.contains("unexpected end of file"), "{e}");

    let e = read_node("3 3 0 0\n", "dim.node").unwrap_err();
    assert!(e.message.contains("two-dimensional"), "{e}");
    assert_eq!(e.line, Some(1));

    let e = read_node("-3 2 0 0\n", "neg.node").unwrap_err();
    assert!(e.message.contains("negative"), "{e}");

    let e = read_node("3 2 0 0\n1 0 0\n2 - 1\n3 0 1\n", "dash.node").unwrap_err();
    assert!(
        e.message.contains("not a number") && e.line == Some(3),
        "{e}"
    );

    let e = read_node("3 2 0 0\n1 0 0\n2 1e999 1\n3 0 1\n", "inf.node").unwrap_err();
    assert!(e.message.contains("not a finite number"), "{e}");

    let e = read_node("", "empty.node").unwrap_err();
    assert!(e.message.contains("unexpected end of file"), "{e}");
}

#[test]
fn ele_and_index_checks() {
    let text = "2 3 1\n1 1 2 3 0.5\n2 3 4 1\n";
    let ele = read_ele(text, "x.ele").unwrap();
    assert_eq!(ele.corners, 3);
    assert_eq!(ele.triangles, vec![1, 2, 3, 3, 4, 1]);
    assert_eq!(ele.attributes, vec![0.5, 0.0]);
    assert_eq!(ele.lines, vec![2, 3]);
    assert!(check_vertex_indices("x.ele", "triangle", &ele.triangles, 3, &ele.lines, 1, 4).is_ok());
    let e =
        check_vertex_indices("x.ele", "triangle", &ele.triangles, 3, &ele.lines, 1, 3).unwrap_err();
    assert_eq!(e.line, Some(3));
    assert!(e.message.contains("triangle 2 refers to vertex 4"), "{e}");
    let e =
        check_vertex_indices("x.ele", "triangle", &ele.triangles, 3, &ele.lines, 0, 4).unwrap_err();
    assert!(e.message.contains("vertex 4"), "{e}");

    let e = read_ele("1 3 0\n1 1 2\n", "m.ele").unwrap_err();
    assert!(e.message.contains("node 3 of triangle 1 is missing"), "{e}");
    let e = read_ele("1 2 0\n1 1 2\n", "c.ele").unwrap_err();
    assert!(e.message.contains("at least 3"), "{e}");

    let six = read_ele("1 6\n0 0 1 2 3 4 5\n", "six.ele").unwrap();
    assert_eq!(six.triangle_count(), 1);
    assert_eq!(six.first_number, Some(0));
}

#[test]
fn poly_sections() {
    let text = "\
# square with a hole and two regions
4 2 0 1
1 0 0 1
2 2 0 1
3 2 2 1
4 0 2 1
4 1
1 1 2 5
2 2 3 5
3 3 4
4 4 1 6
1
1 1.0 1.0
2
1 0.5 0.5 7 0.25
2 1.5 1.5 9
";
    let poly = read_poly(text, "sq.poly", true).unwrap();
    assert_eq!(poly.vertices.point_count(), 4);
    assert_eq!(poly.segments, vec![1, 2, 2, 3, 3, 4, 4, 1]);
    assert_eq!(poly.segment_markers, Some(vec![5, 5, 0, 6]));
    assert_eq!(poly.segment_lines, vec![8, 9, 10, 11]);
    assert_eq!(poly.holes, vec![1.0, 1.0]);
    assert_eq!(poly.regions, vec![0.5, 0.5, 7.0, 0.25, 1.5, 1.5, 9.0, 9.0]);

    let without_regions = read_poly(text, "sq.poly", false).unwrap();
    assert!(without_regions.regions.is_empty());

    // No vertices (they come from the .node file), no region section even when asked for.
    let empty = read_poly("0 2 0 1\n1 0\n1 1 2\n0\n", "e.poly", true).unwrap();
    assert_eq!(empty.vertices.point_count(), 0);
    assert_eq!(empty.vertices.first_number, None);
    assert_eq!(empty.segments, vec![1, 2]);
    assert_eq!(empty.segment_markers, None);

    let e = read_poly("0 2 0 0\n1 0\n1 1\n0\n", "s.poly", false).unwrap_err();
    assert!(
        e.message
            .contains("second endpoint of segment 1 is missing"),
        "{e}"
    );
    let e = read_poly("0 2 0 0\n1 0\n1 1 2\n", "h.poly", false).unwrap_err();
    assert!(
        e.message.contains("unexpected end of file") && e.message.contains("hole"),
        "{e}"
    );
    let e = read_poly("0 2 0 0\n0 0\n0\n1\n1 0.5 0.5\n", "r.poly", true).unwrap_err();
    assert!(
        e.message
            .contains("attribute (or area constraint) of region 1"),
        "{e}"
    );
}

#[test]
fn output_formats_read_back() {
    let area = read_area("2\n1 0.5\n2 -1\n", "a.area").unwrap();
    assert_eq!(area.areas, vec![0.5, -1.0]);
    let edge = read_edge("2  1\n   1   4  1  1\n   2   1  5  0\n", "x.edge").unwrap();
    assert_eq!(edge.edges, vec![4, 1, 1, 5]);
    assert_eq!(edge.markers, Some(vec![1, 0]));
    let v = read_voronoi_edge("2  0\n   1   1  -1   -1  0\n   2   1  3\n", "x.v.edge").unwrap();
    assert_eq!(v.edges, vec![1, -1, 1, 3]);
    assert_eq!(v.norms, vec![-1.0, 0.0, 0.0, 0.0]);
    let n = read_neigh("1  3\n   1    -1  2  -1\n", "x.neigh").unwrap();
    assert_eq!(n.neighbors, vec![-1, 2, -1]);
    let off = read_off(
        "OFF\n3  1  3\n 0  0  0\n 1  0  0\n 0  1  0\n 3      0     1     2\n",
        "x.off",
    )
    .unwrap();
    assert_eq!(off.points.len(), 9);
    assert_eq!(off.triangles, vec![0, 1, 2]);
    assert_eq!(off.edge_count, 3);
}

#[test]
fn a_leading_byte_order_mark_is_skipped_in_every_file_kind() {
    const BOM: &str = "\u{feff}";
    let with_bom = |text: &str| format!("{BOM}{text}");
    let node = "4 2 1 1\n1 0 0 0.5 1\n2 1 0 1 0\n3 1 1 2 0\n4 0 1 3 1\n";
    assert_eq!(
        read_node(&with_bom(node), "b.node"),
        read_node(node, "b.node")
    );
    // A first line that is a comment, or that starts with blanks.
    for start in ["# saved by an editor\n", "  "] {
        let text = format!("{start}{node}");
        assert_eq!(
            read_node(&with_bom(&text), "b.node"),
            read_node(&text, "b.node")
        );
    }
    let poly = "4 2 0 1\n1 0 0 1\n2 1 0 1\n3 1 1 1\n4 0 1 1\n4 1\n1 1 2 1\n2 2 3 1\n\
                3 3 4 1\n4 4 1 1\n1\n1 0.5 0.5\n1\n1 0.2 0.2 3 0.1\n";
    assert_eq!(
        read_poly(&with_bom(poly), "b.poly", true),
        read_poly(poly, "b.poly", true)
    );
    // A `.poly` whose vertices are in the `.node` file.
    let poly = "0 2 0 0\n1 0\n1 1 2\n0\n";
    assert_eq!(
        read_poly(&with_bom(poly), "b.poly", false),
        read_poly(poly, "b.poly", false)
    );
    let ele = "2 3 1\n1 4 1 2 0.5\n2 2 3 4 1\n";
    assert_eq!(read_ele(&with_bom(ele), "b.ele"), read_ele(ele, "b.ele"));
    let area = "2\n1 0.5\n2 -1\n";
    assert_eq!(
        read_area(&with_bom(area), "b.area"),
        read_area(area, "b.area")
    );
    let edge = "2 1\n1 4 1 1\n2 1 5 0\n";
    assert_eq!(
        read_edge(&with_bom(edge), "b.edge"),
        read_edge(edge, "b.edge")
    );
    let voronoi = "2 0\n1 1 -1 -1 0\n2 1 3\n";
    assert_eq!(
        read_voronoi_edge(&with_bom(voronoi), "b.v.edge"),
        read_voronoi_edge(voronoi, "b.v.edge")
    );
    let neigh = "1 3\n1 -1 2 -1\n";
    assert_eq!(
        read_neigh(&with_bom(neigh), "b.neigh"),
        read_neigh(neigh, "b.neigh")
    );
    let off = "OFF\n3 1 3\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    assert_eq!(read_off(&with_bom(off), "b.off"), read_off(off, "b.off"));
    // Line numbers do not move: the mark is no line of its own.
    let e = read_node(&with_bom("3 2 0 0\n1 0 0\n2 1\n3 0 1\n"), "e.node").unwrap_err();
    assert_eq!(e.line, Some(3), "{e}");
    // A large vertex section, read by the fast path on two threads, reads the same.
    let large = varied_node_text(120_000, 1, true, 9);
    assert_eq!(
        read_node(&with_bom(&large), "l.node"),
        read_node(&large, "l.node")
    );
}

/// A small seeded generator for the tests below.
fn next(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A real in one of many spellings, most of them plain.
fn spelled_real(state: &mut u64) -> String {
    let x = (next(state) >> 11) as f64 / (1u64 << 53) as f64;
    let spellings = [
        crate::io::files::g17(x),
        crate::io::files::g17(-x * 1e6),
        format!("{x:e}"),
        format!("{:E}", x * 1e-300),
        format!("{:.3}", x * 100.0),
        format!("+{:.2}", x),
        format!("{}", (next(state) % 1000) as i64 - 500),
        ".5".to_string(),
        "7.".to_string(),
        "-0".to_string(),
        "1.e5".to_string(),
        "2e".to_string(),
        "0.125x".to_string(),
        "00012.5".to_string(),
        "123456789012345678901234567890".to_string(),
        "0.1000000000000000055511151231257827021181583404541015625".to_string(),
        "4.9406564584124654e-324".to_string(),
        "1.7976931348623157e308".to_string(),
    ];
    let k = next(state) % 40;
    spellings[if k < 20 {
        0
    } else {
        (k as usize - 20) % spellings.len()
    }]
    .clone()
}

/// A `.node` text of `count` rows, most of them plain, with every kind of line the general
/// reader accepts sprinkled in (and, with `errors`, a few that it rejects).
fn varied_node_text(count: usize, attributes: usize, markers: bool, seed: u64) -> String {
    let mut state = seed;
    let mut text = format!(
        "# header next\n{count} 2 {attributes} {}\n",
        u8::from(markers)
    );
    for v in 0..count {
        let odd = next(&mut state) % 50 == 0;
        if odd {
            match next(&mut state) % 6 {
                0 => text.push('\n'),
                1 => text.push_str("   # a comment line\n"),
                2 => text.push_str("\t\r\n"),
                _ => {}
            }
        }
        let separator = if odd && next(&mut state) % 2 == 0 {
            "\t"
        } else {
            "  "
        };
        let number = match next(&mut state) % 150 {
            0 => format!("0x{:x}", v + 1),
            1 => format!("0{:o}", v + 1),
            2 => format!("+{}", v + 1),
            _ => format!("{}", v + 1),
        };
        text.push_str(&number);
        for _ in 0..2 + attributes {
            text.push_str(separator);
            text.push_str(&spelled_real(&mut state));
        }
        if markers && !(odd && next(&mut state) % 4 == 0) {
            text.push_str(separator);
            let marker = match next(&mut state) % 60 {
                0 => "010".to_string(),
                2 => "-0".to_string(),
                _ => format!("{}", (next(&mut state) % 7) as i64 - 3),
            };
            text.push_str(&marker);
        }
        if odd {
            match next(&mut state) % 5 {
                0 => text.push_str("  # trailing comment"),
                1 => text.push_str(" extra 1 2 3"),
                2 => text.push('\r'),
                _ => {}
            }
        }
        text.push('\n');
    }
    text
}

/// Every line made unplain (a leading word that does not start like a number, which the
/// general reader skips): read by the general reader alone.
fn general_only(text: &str) -> String {
    text.lines().map(|line| format!("x {line}\n")).collect()
}

#[test]
fn plain_rows_read_as_the_general_reader_reads_them() {
    for (count, attributes, markers) in [
        (1, 0, false),
        (500, 0, true),
        (3000, 2, true),
        (2000, 9, false),
        (150_000, 0, true),
        (120_000, 1, false),
    ] {
        let text = varied_node_text(count, attributes, markers, count as u64);
        let fast = read_node(&text, "v.node");
        let general = read_node(&general_only(&text), "v.node");
        match (&fast, &general) {
            (Ok(a), Ok(b)) => {
                assert_eq!(a.first_number, b.first_number);
                assert_eq!(a.markers, b.markers);
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&a.points), bits(&b.points), "{count} rows");
                assert_eq!(bits(&a.attributes), bits(&b.attributes), "{count} rows");
            }
            _ => assert_eq!(fast, general),
        }
    }
}

#[test]
fn large_sections_read_on_two_threads_keep_line_numbers_and_what_follows() {
    // Errors before, at and after the middle of a large section name their lines.
    let count = 200_000;
    let text = varied_node_text(count, 0, true, 5);
    for fraction in [0.1, 0.5, 0.50001, 0.50002, 0.9] {
        let line = (fraction * text.lines().count() as f64) as usize;
        let broken: String = text
            .lines()
            .enumerate()
            .map(|(i, l)| {
                if i == line && l.starts_with(|c: char| c.is_ascii_digit()) {
                    let number = l.split_whitespace().next().unwrap();
                    match i % 2 {
                        0 => format!("{number} 0.5 1e999 1\n"),
                        _ => format!("{number} 0.5 0.5 3000000000\n"),
                    }
                } else {
                    format!("{l}\n")
                }
            })
            .collect();
        let fast = read_node(&broken, "b.node");
        let general = read_node(&general_only(&broken), "b.node");
        assert_eq!(fast, general);
    }
    // A file that ends early.
    let cut = &text[..text.len() * 2 / 3];
    let cut = &cut[..cut.rfind('\n').unwrap() + 1];
    assert_eq!(
        read_node(cut, "c.node"),
        read_node(&general_only(cut), "c.node")
    );
    // A `.poly` file: the segments after a large vertex section are read as segments.
    let mut poly = format!("{count} 2 0 0\n");
    for v in 0..count {
        poly.push_str(&format!("{} {} {}\n", v + 1, v % 1000, v / 1000));
    }
    poly.push_str(&format!("{count} 1\n"));
    for s in 0..count {
        poly.push_str(&format!("{} {} {} 1\n", s + 1, s + 1, (s + 1) % count + 1));
    }
    poly.push_str("0\n");
    let read = read_poly(&poly, "p.poly", false).unwrap();
    assert_eq!(read.vertices.point_count(), count);
    assert_eq!(
        read.vertices.points[2 * (count - 1)],
        ((count - 1) % 1000) as f64
    );
    assert_eq!(read.segments.len(), 2 * count);
    assert_eq!(read.segment_lines[0] as usize, count + 3);
    // A `.poly` whose vertex section is short against its segments.
    let mut poly = format!("{count} 2 0 0\n");
    for v in 0..count {
        poly.push_str(&format!("{} {} {}\n", v + 1, v, 0));
    }
    poly.push_str(&format!("{} 0\n", 4 * count));
    for s in 0..4 * count {
        poly.push_str(&format!(
            "{} {} {}\n",
            s + 1,
            s % count + 1,
            (s + 1) % count + 1
        ));
    }
    poly.push_str("0\n");
    let read = read_poly(&poly, "q.poly", false).unwrap();
    assert_eq!(read.vertices.point_count(), count);
    assert_eq!(read.segments.len(), 8 * count);
    assert_eq!(read.segment_lines[0] as usize, count + 3);
}
