//! The declaration file's `profile`: one device (`profile = "desktop"`) or several
//! (`profile = ["webgpu", "desktop"]`, one verdict per device), for the tree or for one pass.

use serde::Deserialize;
use toml::Spanned;

use super::DeclarationError;
use crate::diagnostic::Span;
use crate::validator::Profile;

/// `profile`'s value as written: a name, or a list of names each with its place.
pub(super) enum ProfileToml {
    /// `profile = "desktop"`.
    One(String),
    /// `profile = ["webgpu", "desktop"]`.
    Many(Vec<Spanned<String>>),
}

impl<'de> Deserialize<'de> for ProfileToml {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = ProfileToml;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(
                    "a profile (`webgpu`, `webgl2`, `desktop` or naga capability names joined by `,`) or a list of profiles",
                )
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<ProfileToml, E> {
                Ok(ProfileToml::One(v.to_string()))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<ProfileToml, A::Error> {
                let mut names = Vec::new();
                while let Some(name) = seq.next_element::<Spanned<String>>()? {
                    names.push(name);
                }
                Ok(ProfileToml::Many(names))
            }
        }
        d.deserialize_any(Visitor)
    }
}

/// The profiles `value` names, in the order written, each once; empty when it is absent. An
/// unknown name or an empty list is an error at the place written.
pub(super) fn profiles(
    value: Option<&Spanned<ProfileToml>>,
    at: impl Fn(std::ops::Range<usize>) -> Span,
    errors: &mut Vec<DeclarationError>,
) -> Vec<Profile> {
    let Some(value) = value else {
        return Vec::new();
    };
    let names: Vec<(&str, std::ops::Range<usize>)> = match value.get_ref() {
        ProfileToml::One(name) => vec![(name.as_str(), value.span())],
        ProfileToml::Many(names) => names
            .iter()
            .map(|n| (n.get_ref().as_str(), n.span()))
            .collect(),
    };
    if names.is_empty() {
        errors.push(DeclarationError {
            message: "`profile = []` names no device: list at least one profile, or leave `profile` out for WebGPU".into(),
            span: at(value.span()),
        });
    }
    let mut out: Vec<Profile> = Vec::new();
    for (name, range) in names {
        match name.parse::<Profile>() {
            Ok(p) if !out.contains(&p) => out.push(p),
            Ok(_) => {}
            Err(e) => errors.push(DeclarationError {
                message: e.to_string(),
                span: at(range),
            }),
        }
    }
    out
}
