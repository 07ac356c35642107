//! The thesis's XML files (feature `xml`, host only): a scene of Bézier geometry and a
//! mass-spring description that turns one geometry's control points into particles.
//!
//! Scene (`<scene>`): `<node type="geometry" name="...">` holding one
//! `<geometry type="bezier" npu=".." npv="..">` with `npu × npv` `<vertex x=".." y=".." z=".."/>`
//! in row order (`npu` per row). Physics (`<mass-spring>`): attributes `mass` (per particle),
//! `gravity` (along y), `damping` (linear, 1/s), `constant` (spring stiffness), optional
//! `restLength`, and `geometry` (the node name), holding `<connection node1=".." node2=".."/>`.
//!
//! `restLength` sets the rest length of the shortest connection; the others keep their
//! initial proportions. (Read literally, the thesis's single value would make its shear and
//! bending springs as short as its structural ones and crumple the cloth.) Without it every
//! spring rests at its initial length.
//!
//! Every malformed input, from a stray tag to a connection naming a vertex that does not exist,
//! is an [`XmlError`] naming the file, line and column. Nothing is half loaded: a load returns
//! everything or an error.

use std::fmt;
use std::format;
use std::path::Path;
use std::string::{String, ToString};
use std::vec::Vec;

use roxmltree::{Document, Node};

use crate::Settings;
use crate::physics::shape::Grid;
use crate::physics::spring::{Material, Springs};
use crate::{MassSpring, Scalar, Vec3};

/// A load error: where it is and what is wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct XmlError {
    /// The file (as named to the loader).
    pub file: String,
    /// Line, from 1; 0 when the file could not be read at all.
    pub line: u32,
    /// Column, from 1; 0 when the file could not be read at all.
    pub column: u32,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for XmlError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}",
            self.file, self.line, self.column, self.message
        )
    }
}

impl std::error::Error for XmlError {}

/// Position in a file, for errors found after parsing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pos {
    /// Line, from 1.
    pub line: u32,
    /// Column, from 1.
    pub column: u32,
}

/// One Bézier geometry of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Geometry {
    /// The node's name.
    pub name: String,
    /// Control points per row.
    pub npu: usize,
    /// Rows.
    pub npv: usize,
    /// The `npu × npv` control points, row after row.
    pub vertices: Vec<[f64; 3]>,
    /// Where the `<geometry>` element is.
    pub pos: Pos,
}

/// A parsed scene file.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The file name, for errors.
    pub file: String,
    /// The geometries, in file order.
    pub geometries: Vec<Geometry>,
}

/// A connection between two vertices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Connection {
    /// First vertex index.
    pub node1: usize,
    /// Second vertex index.
    pub node2: usize,
    /// Where the element is.
    pub pos: Pos,
}

/// A parsed mass-spring file.
#[derive(Clone, Debug, PartialEq)]
pub struct Physics {
    /// The file name, for errors.
    pub file: String,
    /// Mass of each particle (> 0).
    pub mass: f64,
    /// Gravity along y (units/s²).
    pub gravity: f64,
    /// Linear damping rate (1/s, >= 0).
    pub damping: f64,
    /// Spring stiffness (> 0).
    pub constant: f64,
    /// Rest length of the shortest connection, if given (> 0).
    pub rest_length: Option<f64>,
    /// The geometry these particles belong to.
    pub geometry: String,
    /// Where the `geometry` attribute is.
    pub geometry_pos: Pos,
    /// The springs.
    pub connections: Vec<Connection>,
}

struct Ctx<'a, 'input> {
    file: &'a str,
    doc: &'a Document<'input>,
}

impl Ctx<'_, '_> {
    fn at(&self, offset: usize) -> Pos {
        let p = self.doc.text_pos_at(offset);
        Pos {
            line: p.row,
            column: p.col,
        }
    }

    fn err_at(&self, pos: Pos, message: impl Into<String>) -> XmlError {
        XmlError {
            file: self.file.into(),
            line: pos.line,
            column: pos.column,
            message: message.into(),
        }
    }

    fn err(&self, node: Node<'_, '_>, message: impl Into<String>) -> XmlError {
        self.err_at(self.at(node.range().start), message)
    }

    /// Fails on any attribute not in `allowed`.
    fn only_attributes(&self, node: Node<'_, '_>, allowed: &[&str]) -> Result<(), XmlError> {
        for a in node.attributes() {
            if !allowed.contains(&a.name()) {
                let msg = format!(
                    "unknown attribute `{}` on <{}>",
                    a.name(),
                    node.tag_name().name()
                );
                return Err(self.err_at(self.at(a.range().start), msg));
            }
        }
        Ok(())
    }

    fn text_attr<'n>(&self, node: Node<'n, '_>, name: &str) -> Result<&'n str, XmlError> {
        node.attribute(name).ok_or_else(|| {
            self.err(
                node,
                format!(
                    "<{}> is missing the `{name}` attribute",
                    node.tag_name().name()
                ),
            )
        })
    }

    fn attr_pos(&self, node: Node<'_, '_>, name: &str) -> Pos {
        node.attribute_node(name).map_or_else(
            || self.at(node.range().start),
            |a| self.at(a.range_value().start),
        )
    }

    fn number(&self, node: Node<'_, '_>, name: &str) -> Result<f64, XmlError> {
        let text = self.text_attr(node, name)?;
        let pos = self.attr_pos(node, name);
        let v: f64 = text
            .trim()
            .parse()
            .map_err(|_| self.err_at(pos, format!("`{name}` is not a number: {text:?}")))?;
        if !v.is_finite() {
            return Err(self.err_at(pos, format!("`{name}` must be finite, not {text}")));
        }
        Ok(v)
    }

    fn positive(&self, node: Node<'_, '_>, name: &str) -> Result<f64, XmlError> {
        let v = self.number(node, name)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(self.err_at(
                self.attr_pos(node, name),
                format!("`{name}` must be positive"),
            ))
        }
    }

    fn index(&self, node: Node<'_, '_>, name: &str) -> Result<usize, XmlError> {
        let text = self.text_attr(node, name)?;
        text.trim().parse().map_err(|_| {
            self.err_at(
                self.attr_pos(node, name),
                format!("`{name}` is not a vertex index: {text:?}"),
            )
        })
    }

    /// The element children, failing on any element not named `tag` and on stray text.
    fn children<'n, 'i>(
        &self,
        node: Node<'n, 'i>,
        tag: &str,
    ) -> Result<Vec<Node<'n, 'i>>, XmlError> {
        let mut out = Vec::new();
        for c in node.children() {
            if c.is_element() {
                if c.tag_name().name() != tag {
                    let msg = format!(
                        "unknown tag <{}> in <{}> (expected <{tag}>)",
                        c.tag_name().name(),
                        node.tag_name().name()
                    );
                    return Err(self.err(c, msg));
                }
                out.push(c);
            } else if c.is_text() && !c.text().unwrap_or("").trim().is_empty() {
                return Err(self.err(
                    c,
                    format!("unexpected text in <{}>", node.tag_name().name()),
                ));
            }
        }
        Ok(out)
    }
}

fn parse_doc<'i>(text: &'i str, file: &str) -> Result<Document<'i>, XmlError> {
    Document::parse(text).map_err(|e| {
        let p = e.pos();
        XmlError {
            file: file.into(),
            line: p.row,
            column: p.col,
            message: format!("malformed XML: {e}"),
        }
    })
}

fn root_named<'a, 'i>(ctx: &Ctx<'a, 'i>, tag: &str) -> Result<Node<'a, 'i>, XmlError> {
    let root = ctx.doc.root_element();
    if root.tag_name().name() != tag {
        return Err(ctx.err(
            root,
            format!(
                "unknown tag <{}> at the top (expected <{tag}>)",
                root.tag_name().name()
            ),
        ));
    }
    Ok(root)
}

fn read(path: &Path) -> Result<String, XmlError> {
    std::fs::read_to_string(path).map_err(|e| XmlError {
        file: path.display().to_string(),
        line: 0,
        column: 0,
        message: format!("cannot read the file: {e}"),
    })
}

/// Parses a scene from text; `file` names it in errors.
///
/// # Errors
/// An [`XmlError`] at the first problem: malformed XML, an unknown tag or attribute, a missing
/// or unparsable attribute, a NaN or infinite coordinate, a vertex count other than
/// `npu × npv`, a duplicate node name.
pub fn parse_scene(text: &str, file: &str) -> Result<Scene, XmlError> {
    let doc = parse_doc(text, file)?;
    let ctx = Ctx { file, doc: &doc };
    let root = root_named(&ctx, "scene")?;
    ctx.only_attributes(root, &[])?;
    let mut geometries: Vec<Geometry> = Vec::new();
    for node in ctx.children(root, "node")? {
        ctx.only_attributes(node, &["type", "name"])?;
        if ctx.text_attr(node, "type")? != "geometry" {
            return Err(ctx.err_at(
                ctx.attr_pos(node, "type"),
                "only nodes of type \"geometry\" are supported",
            ));
        }
        let name = ctx.text_attr(node, "name")?.to_string();
        if name.is_empty() || geometries.iter().any(|g| g.name == name) {
            return Err(ctx.err_at(
                ctx.attr_pos(node, "name"),
                format!("node name {name:?} is empty or used twice"),
            ));
        }
        let geoms = ctx.children(node, "geometry")?;
        let [geom] = geoms[..] else {
            return Err(ctx.err(
                node,
                format!("node {name:?} must hold exactly one <geometry>"),
            ));
        };
        ctx.only_attributes(geom, &["type", "npu", "npv", "physics"])?;
        if ctx.text_attr(geom, "type")? != "bezier" {
            return Err(ctx.err_at(
                ctx.attr_pos(geom, "type"),
                "only geometry of type \"bezier\" is supported",
            ));
        }
        let (npu, npv) = (ctx.index(geom, "npu")?, ctx.index(geom, "npv")?);
        if !(2..=256).contains(&npu) || !(2..=256).contains(&npv) {
            return Err(ctx.err(geom, "npu and npv must be 2 to 256"));
        }
        let mut vertices = Vec::with_capacity(npu * npv);
        for v in ctx.children(geom, "vertex")? {
            ctx.only_attributes(v, &["x", "y", "z"])?;
            vertices.push([
                ctx.number(v, "x")?,
                ctx.number(v, "y")?,
                ctx.number(v, "z")?,
            ]);
        }
        if vertices.len() != npu * npv {
            let msg = format!(
                "{} vertices, but npu × npv = {npu} × {npv} = {}",
                vertices.len(),
                npu * npv
            );
            return Err(ctx.err(geom, msg));
        }
        geometries.push(Geometry {
            name,
            npu,
            npv,
            vertices,
            pos: ctx.at(geom.range().start),
        });
    }
    Ok(Scene {
        file: file.into(),
        geometries,
    })
}

/// Parses a mass-spring description from text; `file` names it in errors.
///
/// # Errors
/// An [`XmlError`] at the first problem: malformed XML, an unknown tag or attribute, a missing,
/// unparsable, NaN, infinite or out-of-range attribute, a connection of a vertex to itself or a
/// duplicate connection.
pub fn parse_physics(text: &str, file: &str) -> Result<Physics, XmlError> {
    let doc = parse_doc(text, file)?;
    let ctx = Ctx { file, doc: &doc };
    let root = root_named(&ctx, "mass-spring")?;
    ctx.only_attributes(
        root,
        &[
            "mass",
            "gravity",
            "damping",
            "constant",
            "restLength",
            "geometry",
        ],
    )?;
    let damping = ctx.number(root, "damping")?;
    if damping < 0.0 {
        return Err(ctx.err_at(
            ctx.attr_pos(root, "damping"),
            "`damping` must not be negative",
        ));
    }
    let rest_length = match root.attribute("restLength") {
        Some(_) => Some(ctx.positive(root, "restLength")?),
        None => None,
    };
    let mut connections: Vec<Connection> = Vec::new();
    for c in ctx.children(root, "connection")? {
        ctx.only_attributes(c, &["node1", "node2"])?;
        let (node1, node2) = (ctx.index(c, "node1")?, ctx.index(c, "node2")?);
        let pos = ctx.at(c.range().start);
        let (lo, hi) = (node1.min(node2), node1.max(node2));
        if node1 == node2
            || connections
                .iter()
                .any(|k| k.node1.min(k.node2) == lo && k.node1.max(k.node2) == hi)
        {
            return Err(ctx.err_at(pos, format!("duplicate connection {node1}-{node2}")));
        }
        connections.push(Connection { node1, node2, pos });
    }
    Ok(Physics {
        file: file.into(),
        mass: ctx.positive(root, "mass")?,
        gravity: ctx.number(root, "gravity")?,
        damping,
        constant: ctx.positive(root, "constant")?,
        rest_length,
        geometry: ctx.text_attr(root, "geometry")?.to_string(),
        geometry_pos: ctx.attr_pos(root, "geometry"),
        connections,
    })
}

/// Reads and parses a scene file.
///
/// # Errors
/// As [`parse_scene`], and an error at line 0 when the file cannot be read.
pub fn load_scene(path: &Path) -> Result<Scene, XmlError> {
    parse_scene(&read(path)?, &path.display().to_string())
}

/// Reads and parses a mass-spring file.
///
/// # Errors
/// As [`parse_physics`], and an error at line 0 when the file cannot be read.
pub fn load_physics(path: &Path) -> Result<Physics, XmlError> {
    parse_physics(&read(path)?, &path.display().to_string())
}

/// A cloth of compile-time size `U × V` (room for `CAP` springs) from the geometry the
/// physics file names: particles at its control points, one spring per connection, nothing
/// pinned (pin with [`MassSpring::set_inv_mass`]).
///
/// # Errors
/// An [`XmlError`] when the geometry name does not resolve, when its `npu × npv` is not
/// `U × V`, when a connection names a vertex past the count or two vertices at the same place,
/// when there are more connections than `CAP`, or when a coordinate is out of the format's range.
pub fn build_cloth<S: Scalar, const U: usize, const V: usize, const CAP: usize>(
    scene: &Scene,
    physics: &Physics,
) -> Result<MassSpring<Vec3<S>, Grid<U, V>, Springs<S, CAP>>, XmlError> {
    let perr = |pos: Pos, message: String| XmlError {
        file: physics.file.clone(),
        line: pos.line,
        column: pos.column,
        message,
    };
    let geom = scene
        .geometries
        .iter()
        .find(|g| g.name == physics.geometry)
        .ok_or_else(|| {
            perr(
                physics.geometry_pos,
                format!("no geometry named {:?} in {}", physics.geometry, scene.file),
            )
        })?;
    if (geom.npu, geom.npv) != (U, V) {
        return Err(XmlError {
            file: scene.file.clone(),
            line: geom.pos.line,
            column: geom.pos.column,
            message: format!(
                "geometry is {} × {}, but this cloth is built for {U} × {V}",
                geom.npu, geom.npv
            ),
        });
    }
    let at = |k: usize| geom.vertices[k];
    let dist = |a: [f64; 3], b: [f64; 3]| {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    let mut shortest = f64::INFINITY;
    for c in &physics.connections {
        for n in [c.node1, c.node2] {
            if n >= geom.vertices.len() {
                return Err(perr(
                    c.pos,
                    format!(
                        "vertex {n} does not exist ({} vertices)",
                        geom.vertices.len()
                    ),
                ));
            }
        }
        shortest = shortest.min(dist(at(c.node1), at(c.node2)));
    }
    let scale = match physics.rest_length {
        Some(r) if shortest > 0.0 && shortest.is_finite() => r / shortest,
        _ => 1.0,
    };
    let material = Material {
        stiffness: S::from_f64(physics.constant),
        damping: S::ZERO,
    };
    material
        .check()
        .map_err(|e| perr(physics.geometry_pos, format!("stiffness: {e}")))?;
    let mut springs = Springs::new(material);
    for c in &physics.connections {
        let rest = S::from_f64(dist(at(c.node1), at(c.node2)) * scale);
        springs
            .connect_with_rest(U * V, c.node1, c.node2, rest)
            .map_err(|e| perr(c.pos, format!("connection {}-{}: {e}", c.node1, c.node2)))?;
    }
    let mut positions = [[Vec3::default(); U]; V];
    for (k, v) in geom.vertices.iter().enumerate() {
        positions[k / U][k % U] = Vec3::from_f64(v[0], v[1], v[2]);
    }
    let settings = Settings {
        gravity: Vec3::from_f64(0.0, physics.gravity, 0.0),
        damping: S::from_f64(physics.damping),
        ..Settings::default()
    };
    let w = S::from_f64(1.0 / physics.mass);
    MassSpring::new(positions, [[w; U]; V], springs, settings).map_err(|e| XmlError {
        file: scene.file.clone(),
        line: geom.pos.line,
        column: geom.pos.column,
        message: format!("geometry {:?}: {e}", geom.name),
    })
}

/// Shorthand for the tests and examples: both files loaded and built.
///
/// # Errors
/// As [`load_scene`], [`load_physics`] and [`build_cloth`].
pub fn load_cloth<S: Scalar, const U: usize, const V: usize, const CAP: usize>(
    scene: &Path,
    physics: &Path,
) -> Result<MassSpring<Vec3<S>, Grid<U, V>, Springs<S, CAP>>, XmlError> {
    build_cloth(&load_scene(scene)?, &load_physics(physics)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_are_one_based() {
        let e = parse_scene("<scene>\n  <bogus/>\n</scene>", "s.xml").unwrap_err();
        assert_eq!((e.line, e.column), (2, 3));
        assert_eq!(
            e.to_string(),
            "s.xml:2:3: unknown tag <bogus> in <scene> (expected <node>)"
        );
    }
}
