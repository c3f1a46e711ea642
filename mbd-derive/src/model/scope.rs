//! The names user expressions see: parameters, coordinates (free, driven, relaxed) and
//! points, as symbols of one graph with their roles. `Scope` is the state every later phase
//! shares: the graph, the roles, the names and the errors collected so far.

use super::Ast;
use super::{Coord, CoordKind, Names, Role};
use crate::lower::{self, Binding, Context, Lowerer, Value};
use crate::parse::{Dim, Errors};
use crate::sym::{Expr, Graph, Sym};
use std::collections::HashMap;
use syn::Ident;

pub(super) struct Scope {
    pub g: Graph,
    pub roles: HashMap<Sym, Role>,
    pub names: Names,
    pub struct_name: String,
    pub t: Expr,
    pub dim: Dim,
    pub errors: Errors,
}

impl Scope {
    pub fn new(ast: &Ast, errors: Errors) -> Scope {
        let mut g = Graph::new();
        let t = g.symbol("t");
        let mut scope = Scope {
            g,
            roles: HashMap::new(),
            names: HashMap::new(),
            struct_name: ast.ident.to_string(),
            t,
            dim: ast.dim,
            errors,
        };
        scope.role(t, Role::Time);
        scope
    }

    /// Gives symbol `e` its role in generated code.
    pub fn role(&mut self, e: Expr, role: Role) {
        self.roles.insert(self.g.as_sym(e).expect("symbol"), role);
    }

    /// A lowerer of user expressions over this scope's names, with body queries answered by
    /// `model` (none: kinematics and constants only).
    pub fn lowerer<'a>(&'a mut self, model: Option<&'a mut dyn lower::Model>) -> Lowerer<'a> {
        Lowerer {
            g: &mut self.g,
            names: &self.names,
            struct_name: &self.struct_name,
            model,
            errors: &mut self.errors,
        }
    }

    /// Binds a user name, refusing `t` and duplicates.
    pub fn declare(&mut self, id: &Ident, b: Binding) {
        let key = id.to_string();
        if key == "t" {
            self.errors
                .at(id.span(), "`t` is time and cannot be redefined");
        } else if let std::collections::hash_map::Entry::Vacant(slot) =
            self.names.entry(key.clone())
        {
            slot.insert(b);
        } else {
            self.errors.at(id.span(), format!("duplicate name `{key}`"));
        }
    }

    /// A symbol per parameter; a default must fold to a number.
    pub fn parameters(&mut self, ast: &Ast) {
        for p in &ast.params {
            let s = self.g.symbol(&p.name.to_string());
            self.role(s, Role::Param(p.name.clone()));
            self.declare(&p.name, Binding::Value(Value::Scalar(s)));
        }
        for p in &ast.params {
            let Some(d) = &p.default else { continue };
            let mut scratch = Errors::default();
            let no_names = HashMap::new();
            let v = Lowerer {
                g: &mut self.g,
                names: &no_names,
                struct_name: &self.struct_name,
                model: None,
                errors: &mut scratch,
            }
            .scalar(d, Context::Constant);
            if v.and_then(|v| self.g.as_const(v)).is_none() {
                self.errors.over(
                    d,
                    format!(
                        "the default of `{}` must be a number or a constant expression of numbers",
                        p.name
                    ),
                );
            }
        }
    }

    /// The full coordinates `z = (free, driven, relaxed)`; a driven one with its law.
    pub fn coordinates(&mut self, ast: &Ast) -> Vec<Coord> {
        let mut coords: Vec<Coord> = Vec::new();
        for (i, id) in ast.coords.iter().enumerate() {
            if ast.drives.iter().any(|d| d.name == *id) {
                self.errors.at(
                    id.span(),
                    format!("coordinate `{id}` is both free (in `coords`) and driven (in `drive`): a driven coordinate is a known function of time, remove it from `coords`"),
                );
            }
            let c = new_coord(&mut self.g, id, CoordKind::Free);
            for (s, role) in [
                (c.z, Role::Q(i)),
                (c.zd, Role::Qd(i)),
                (c.zdd, Role::Qdd(i)),
            ] {
                self.role(s, role);
            }
            self.declare(id, Binding::Coord(c.z));
            coords.push(c);
        }
        for d in &ast.drives {
            if ast.coords.contains(&d.name) {
                continue;
            }
            let law = self.lowerer(None).scalar(&d.expr, Context::Constant);
            let c = new_coord(
                &mut self.g,
                &d.name,
                CoordKind::Driven(law.unwrap_or(self.t)),
            );
            self.declare(&d.name, Binding::Coord(c.z));
            coords.push(c);
        }
        for id in &ast.relaxed {
            let c = new_coord(&mut self.g, id, CoordKind::Relaxed);
            self.declare(id, Binding::Coord(c.z));
            coords.push(c);
        }
        coords
    }

    /// Points, in order: a point may use the points before it.
    pub fn points(&mut self, ast: &Ast) {
        let len = self.dim.len();
        for p in ast.points.iter().filter(|p| p.on.is_none()) {
            let v = self.lowerer(None).vector(&p.at, Context::Kinematics, len);
            if let Some(v) = v {
                self.declare(&p.name, Binding::Value(Value::Vector(v)));
            }
        }
    }

    /// Springs and dampers are named too; their names must not clash with anything else.
    pub fn element_names(&mut self, ast: &Ast) {
        let mut element_names = std::collections::HashSet::new();
        for id in ast
            .springs
            .iter()
            .map(|s| &s.name)
            .chain(ast.dampers.iter().map(|d| &d.name))
        {
            if self.names.contains_key(&id.to_string()) || !element_names.insert(id.to_string()) {
                self.errors.at(id.span(), format!("duplicate name `{id}`"));
            }
        }
    }

    /// Reports the errors so far and starts a new collection: what follows needs a
    /// complete kinematic description.
    pub fn errors_so_far(&mut self) -> syn::Result<()> {
        std::mem::take(&mut self.errors).finish()
    }
}

fn new_coord(g: &mut Graph, name: &Ident, kind: CoordKind) -> Coord {
    let base = name.to_string();
    Coord {
        name: name.clone(),
        kind,
        z: g.symbol(&base),
        zd: g.symbol(&format!("{base}'")),
        zdd: g.symbol(&format!("{base}''")),
        zddd: g.symbol(&format!("{base}'''")),
    }
}
