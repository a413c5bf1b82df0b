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
