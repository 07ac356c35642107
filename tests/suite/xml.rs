//! The thesis's XML files: the shipped sample loads, and every kind of malformed input ends in
//! an error naming the file, line and column (never a panic, never half a scene).
#![cfg(feature = "xml")]

use std::path::Path;

use dunas::spring::Topology;
use dunas::xml::{self, XmlError};

const SCENE: &str = include_str!("../../examples/data/cloth_scene.xml");
const PHYSICS: &str = include_str!("../../examples/data/cloth_physics.xml");

fn build(scene: &str, physics: &str) -> Result<usize, XmlError> {
    let s = xml::parse_scene(scene, "scene.xml")?;
    let p = xml::parse_physics(physics, "physics.xml")?;
    Ok(xml::build_cloth::<f64, 4, 4, 64>(&s, &p)?
        .topology()
        .spring_count())
}

/// Replaces the first `from` (which must be there) and expects an error at `line:column` in
/// `file` whose message contains `says`.
fn fails(
    scene_edit: Option<(&str, &str)>,
    physics_edit: Option<(&str, &str)>,
    file: &str,
    at: (u32, u32),
    says: &str,
) {
    let edit = |text: &str, e: Option<(&str, &str)>| match e {
        Some((from, to)) => {
            assert!(text.contains(from), "test edit not found: {from}");
            text.replacen(from, to, 1)
        }
        None => text.to_string(),
    };
    let err =
        build(&edit(SCENE, scene_edit), &edit(PHYSICS, physics_edit)).expect_err("should fail");
    assert_eq!(err.file, file, "{err}");
    assert_eq!((err.line, err.column), at, "{err}");
    assert!(err.message.contains(says), "{err}");
}

#[test]
fn the_shipped_sample_loads() {
    assert_eq!(build(SCENE, PHYSICS), Ok(54));
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data");
    let cloth = xml::load_cloth::<f32, 4, 4, 54>(
        &dir.join("cloth_scene.xml"),
        &dir.join("cloth_physics.xml"),
    )
    .unwrap();
    assert_eq!(cloth.positions()[5].x, -2.0);
    assert_eq!(cloth.settings().gravity.y, -4.87);
}

#[test]
fn malformed_xml() {
    fails(
        Some(("</geometry>", "</geometri>")),
        None,
        "scene.xml",
        (22, 5),
        "malformed XML",
    );
}

#[test]
fn unknown_tag() {
    fails(
        Some((
            "<vertex x=\"2.0\" y=\"4.0\"",
            "<vertexx x=\"2.0\" y=\"4.0\"",
        )),
        None,
        "scene.xml",
        (12, 7),
        "unknown tag <vertexx>",
    );
    fails(
        None,
        Some(("<!-- bending -->", "<spring/>")),
        "physics.xml",
        (20, 3),
        "unknown tag <spring>",
    );
}

#[test]
fn unknown_attribute() {
    fails(
        Some(("npu=\"4\"", "npu=\"4\" colour=\"red\"")),
        None,
        "scene.xml",
        (5, 37),
        "unknown attribute `colour`",
    );
}

#[test]
fn missing_attribute() {
    fails(
        Some((
            "<vertex x=\"6.0\" y=\"8.0\" z=\"0.0\"/>",
            "<vertex x=\"6.0\" y=\"8.0\"/>",
        )),
        None,
        "scene.xml",
        (9, 7),
        "missing the `z` attribute",
    );
    fails(
        None,
        Some((" constant=\"3.0\"", "")),
        "physics.xml",
        (4, 1),
        "missing the `constant`",
    );
}

#[test]
fn unparsable_attribute() {
    fails(
        Some(("x=\"-2.0\" y=\"8.0\"", "x=\"-2.0\" y=\"eight\"")),
        None,
        "scene.xml",
        (7, 27),
        "`y` is not a number",
    );
    fails(
        None,
        Some(("node2=\"5\"", "node2=\"five\"")),
        "physics.xml",
        (7, 66),
        "not a vertex index",
    );
    fails(
        None,
        Some(("mass=\"1.5\"", "mass=\"-1.5\"")),
        "physics.xml",
        (4, 20),
        "must be positive",
    );
}

#[test]
fn nan_and_infinite_numbers() {
    fails(
        Some(("x=\"6.0\" y=\"4.0\"", "x=\"NaN\" y=\"4.0\"")),
        None,
        "scene.xml",
        (13, 18),
        "must be finite",
    );
    fails(
        None,
        Some(("gravity=\"-4.87\"", "gravity=\"-inf\"")),
        "physics.xml",
        (4, 34),
        "must be finite",
    );
}

#[test]
fn index_out_of_range() {
    fails(
        None,
        Some(("node1=\"14\" node2=\"15\"", "node1=\"14\" node2=\"16\"")),
        "physics.xml",
        (19, 3),
        "vertex 16 does not exist",
    );
}

#[test]
fn vertex_count_against_npu_npv_and_the_compile_time_size() {
    fails(
        Some(("npu=\"4\" npv=\"4\"", "npu=\"4\" npv=\"5\"")),
        None,
        "scene.xml",
        (5, 5),
        "16 vertices, but npu × npv = 4 × 5 = 20",
    );
    let s = xml::parse_scene(SCENE, "scene.xml").unwrap();
    let p = xml::parse_physics(PHYSICS, "physics.xml").unwrap();
    let err = xml::build_cloth::<f64, 3, 3, 64>(&s, &p).unwrap_err();
    assert_eq!(
        (err.file.as_str(), err.line, err.column),
        ("scene.xml", 5, 5)
    );
    assert!(err.message.contains("built for 3 × 3"), "{err}");
}

#[test]
fn duplicate_connection() {
    fails(
        None,
        Some((
            "<connection node1=\"0\" node2=\"4\"/>",
            "<connection node1=\"1\" node2=\"0\"/>",
        )),
        "physics.xml",
        (6, 37),
        "duplicate connection 1-0",
    );
    fails(
        None,
        Some((
            "<connection node1=\"0\" node2=\"4\"/>",
            "<connection node1=\"3\" node2=\"3\"/>",
        )),
        "physics.xml",
        (6, 37),
        "duplicate connection 3-3",
    );
}

#[test]
fn unresolved_geometry_name() {
    fails(
        None,
        Some(("geometry=\"BezierCloth\"", "geometry=\"BezierSail\"")),
        "physics.xml",
        (4, 98),
        "no geometry named \"BezierSail\"",
    );
}

#[test]
fn too_many_connections_and_zero_rest_length() {
    let s = xml::parse_scene(SCENE, "scene.xml").unwrap();
    let p = xml::parse_physics(PHYSICS, "physics.xml").unwrap();
    let err = xml::build_cloth::<f64, 4, 4, 20>(&s, &p).unwrap_err();
    assert!(
        err.message.contains("more springs than the capacity of 20"),
        "{err}"
    );
    let same = SCENE.replacen(
        "<vertex x=\"-2.0\" y=\"8.0\"",
        "<vertex x=\"-6.0\" y=\"8.0\"",
        1,
    );
    let err = build(&same, PHYSICS).unwrap_err();
    assert!(err.message.contains("zero rest length"), "{err}");
    assert_eq!((err.line, err.column), (6, 3));
}

#[test]
fn missing_file() {
    let err = xml::load_scene(Path::new("no/such/scene.xml")).unwrap_err();
    assert_eq!(
        (err.file.as_str(), err.line, err.column),
        ("no/such/scene.xml", 0, 0)
    );
    assert!(err.message.contains("cannot read"));
}

#[test]
fn wrong_root_element() {
    fails(
        None,
        Some(("<mass-spring mass", "<spring-mass mass")),
        "physics.xml",
        (38, 1),
        "malformed XML",
    );
    let err = xml::parse_physics("<dunas/>", "p.xml").unwrap_err();
    assert!(
        err.message.contains("unknown tag <dunas> at the top"),
        "{err}"
    );
}
