//! Mitsuba's XML as a tree of [`Element`]s: the files read, `<include>`s spliced in,
//! `<default>`s recorded and `$name`s substituted, every element and attribute value knowing
//! the file, line and column it came from.
//!
//! This follows Mitsuba 3's own parser (`src/core/xml.cpp`): a `<default name value>` defines
//! `$name` unless it is already defined (the first definition wins) and applies from where it
//! stands onwards; `$name` is replaced in every attribute value, longer names first; an
//! `<include filename>` is found relative to the main scene's folder and replaced by the
//! children of the included `<scene>` (or by the included root element when that is not a
//! `<scene>`).

use crate::error::{LoadError, line_column};
use crate::hash::Fingerprint;
use crate::limits::Limit;
use crate::paths::{LoadOptions, resolve};
use std::cell::Cell;
use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// Deepest chain of `<include>`s, as in Mitsuba 3 (`MI_XML_INCLUDE_MAX_RECURSION`).
pub const MAX_INCLUDE_DEPTH: usize = 15;

/// Most text `$name`s may add to a scene, over all its values: `<default>`s defined from one
/// another can double a value at each step (`<default name="b" value="$a$a"/>`), which would
/// otherwise reach gigabytes in a few dozen lines.
pub const MAX_SUBSTITUTED: usize = 64 << 20;

/// Deepest nesting of elements, includes counted. Real scenes nest fewer than ten deep (scene,
/// shape, twosided, bsdf, texture, transform, operation); the bound keeps the recursive
/// readers (and the tree's recursive drop) within any thread's stack on hostile input.
pub const MAX_NESTING: usize = 100;

/// Where something is: a file and a 1-based line and column (in characters).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Loc {
    /// The file, as it was opened.
    pub file: Rc<Path>,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
}

impl Loc {
    /// A load error at this place.
    pub fn error(&self, message: impl Into<String>) -> LoadError {
        LoadError {
            file: self.file.to_path_buf(),
            position: Some((self.line, self.column)),
            message: message.into(),
        }
    }

    /// A warning at this place, as one line naming the file.
    pub fn warning(&self, message: impl fmt::Display) -> String {
        format!("{self}: {message}")
    }
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file.display(), self.line, self.column)
    }
}

/// An attribute, its value already substituted.
#[derive(Clone, Debug)]
pub struct Attr {
    /// The attribute's name.
    pub name: String,
    /// Its value, with `$name`s replaced.
    pub value: String,
    /// Where the value starts (inside the quotes).
    pub loc: Loc,
}

/// An element, with includes spliced in and no `<default>` or `<include>` left.
#[derive(Clone, Debug)]
pub struct Element {
    /// The tag name (`bsdf`, `float`, …).
    pub tag: String,
    /// Where the element starts (its `<`).
    pub loc: Loc,
    /// Its attributes, in document order.
    pub attrs: Vec<Attr>,
    /// Its child elements, in document order.
    pub children: Vec<Element>,
}

impl Element {
    /// The attribute `name`, if present.
    pub fn attr(&self, name: &str) -> Option<&Attr> {
        self.attrs.iter().find(|a| a.name == name)
    }

    /// The value of attribute `name`, if present.
    pub fn value(&self, name: &str) -> Option<&str> {
        self.attr(name).map(|a| a.value.as_str())
    }

    /// The attribute `name`, or an error at the element.
    pub fn require(&self, name: &str) -> Result<&Attr, LoadError> {
        self.attr(name).ok_or_else(|| {
            self.loc
                .error(format!("<{}> needs a `{name}` attribute", self.tag))
        })
    }

    /// An error at the first attribute not in `allowed`.
    pub fn allow_attrs(&self, allowed: &[&str]) -> Result<(), LoadError> {
        match self
            .attrs
            .iter()
            .find(|a| !allowed.contains(&a.name.as_str()))
        {
            Some(a) => Err(a.loc.error(format!(
                "unexpected attribute `{}` in <{}> (it takes: {})",
                a.name,
                self.tag,
                allowed.join(", ")
            ))),
            None => Ok(()),
        }
    }
}

/// The `<scene>` of the Mitsuba file at `path`, includes spliced in; the bytes of every file
/// read are added to `inputs`.
pub fn load(
    path: &Path,
    options: &LoadOptions,
    inputs: &mut Fingerprint,
) -> Result<Element, LoadError> {
    let base_dir = path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
    load_from(path, base_dir, None, options, inputs)
}

/// The `<scene>` of Mitsuba XML given as `text` (not read from a file): `label` names it in
/// errors, and includes, like every file name, start from `base_dir`.
pub fn load_text(
    label: &Path,
    base_dir: PathBuf,
    text: String,
    options: &LoadOptions,
    inputs: &mut Fingerprint,
) -> Result<Element, LoadError> {
    load_from(label, base_dir, Some(text), options, inputs)
}

fn load_from(
    path: &Path,
    base_dir: PathBuf,
    given: Option<String>,
    options: &LoadOptions,
    inputs: &mut Fingerprint,
) -> Result<Element, LoadError> {
    let mut loader = Loader {
        options,
        inputs,
        base_dir,
        params: Vec::new(),
        chain: vec![Opened::new(path)],
        depth: 0,
        substituted: Cell::new(0),
        read: 0,
        texts: HashMap::new(),
    };
    if let Some(text) = given {
        // Given text stands where the file would be read: counted and budgeted the same way.
        loader.inputs.add(text.as_bytes());
        let key = Opened::new(path).key;
        loader
            .texts
            .insert(path.to_path_buf(), Rc::new(Text { key, text }));
    }
    let text = loader.text(path, None)?;
    loader.file(path, &text, None)
}

/// A file being read, for the include chain.
struct Opened {
    /// Canonical path, to recognise the same file reached by two names.
    key: PathBuf,
    /// The path as opened, for messages.
    shown: PathBuf,
}

impl Opened {
    fn new(path: &Path) -> Self {
        Self {
            key: std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()),
            shown: path.to_path_buf(),
        }
    }
}

struct Loader<'a> {
    options: &'a LoadOptions,
    inputs: &'a mut Fingerprint,
    /// The main scene's folder: includes (like every file name) start from there.
    base_dir: PathBuf,
    /// `<default>`s so far, in the order given.
    params: Vec<(String, String)>,
    /// The files being read: the main file, then each include in progress.
    chain: Vec<Opened>,
    /// How deep the element being read is nested, includes counted.
    depth: usize,
    /// The bytes `$name`s have added so far.
    substituted: Cell<usize>,
    /// The bytes of XML read so far, includes counted each time (held to
    /// `options.limits.xml_bytes`: a file that includes another a thousand times, which
    /// includes a third a thousand times, would otherwise splice in a billion elements).
    read: u64,
    /// Each file's text and canonical path, by the path it was reached by: a file included
    /// many times is read from disk once.
    texts: HashMap<PathBuf, Rc<Text>>,
}

/// A file's text, read once.
struct Text {
    /// Its canonical path (see [`Opened`]).
    key: PathBuf,
    text: String,
}

impl Loader<'_> {
    /// The text of the file at `path` (included from `from`), read from disk the first time
    /// (and its bytes added to the fingerprint then), and counted against the XML budget each
    /// time, before it is parsed.
    fn text(&mut self, path: &Path, from: Option<&Loc>) -> Result<Rc<Text>, LoadError> {
        let at = |message: String| match from {
            Some(at) => at.error(message),
            None => LoadError::file(path, message),
        };
        let text = match self.texts.get(path) {
            Some(t) => Rc::clone(t),
            None => {
                let bytes = crate::input::read(path).map_err(|e| match from {
                    Some(_) => at(format!(
                        "cannot read the included file `{}`: {e}",
                        path.display()
                    )),
                    None => at(format!("cannot read the scene file: {e}")),
                })?;
                self.inputs.add(&bytes);
                let text = String::from_utf8(bytes).map_err(|e| {
                    LoadError::file(path, format!("the file is not UTF-8 text: {e}"))
                })?;
                let t = Rc::new(Text {
                    key: Opened::new(path).key,
                    text,
                });
                self.texts.insert(path.to_path_buf(), Rc::clone(&t));
                t
            }
        };
        self.read += text.text.len() as u64;
        let limits = &self.options.limits;
        if self.read > limits.xml_bytes {
            return Err(at(limits.exceeded(
                Limit::Xml,
                format!(
                    "the scene and its includes come to {} MiB of XML",
                    self.read.div_ceil(1 << 20)
                ),
            )));
        }
        Ok(text)
    }

    /// The root element of the file at `path` (included from `from`), of text `text`.
    fn file(&mut self, path: &Path, text: &Text, from: Option<&Loc>) -> Result<Element, LoadError> {
        let text = text.text.as_str();
        let file: Rc<Path> = Rc::from(path);
        if let Some(at) = too_deep(text) {
            let (line, column) = line_column(text, at);
            return Err(LoadError {
                file: path.to_path_buf(),
                position: Some((line, column)),
                message: format!("elements are nested more than {MAX_NESTING} deep"),
            });
        }
        let doc = roxmltree::Document::parse(text).map_err(|e| xml_error(path, &e))?;
        let root = doc.root_element();
        let src = Src {
            file: &file,
            text,
            line_starts: std::iter::once(0)
                .chain(text.match_indices('\n').map(|(i, _)| i + 1))
                .collect(),
        };
        let tag = root.tag_name().name();
        if from.is_none() && tag != "scene" {
            return Err(src
                .loc(root.range().start)
                .error(format!("the root element must be <scene>, not <{tag}>")));
        }
        let element = self.element(&src, root)?;
        if tag == "scene" {
            element.allow_attrs(&["version"])?;
            match element.attr("version") {
                Some(v) => check_version(v)?,
                // Mitsuba requires a version on the main file only.
                None if from.is_none() => {
                    return Err(element
                        .loc
                        .error("<scene> needs a `version` attribute (e.g. version=\"3.0.0\")"));
                }
                None => {}
            }
        }
        Ok(element)
    }

    /// `node` and everything under it.
    fn element(&mut self, src: &Src, node: roxmltree::Node) -> Result<Element, LoadError> {
        if self.depth >= MAX_NESTING {
            return Err(src
                .loc(node.range().start)
                .error(format!("elements are nested more than {MAX_NESTING} deep")));
        }
        self.depth += 1;
        let element = self.element_within(src, node);
        self.depth -= 1;
        element
    }

    /// [`Loader::element`] once its depth is checked.
    fn element_within(&mut self, src: &Src, node: roxmltree::Node) -> Result<Element, LoadError> {
        let mut element = Element {
            tag: node.tag_name().name().to_string(),
            loc: src.loc(node.range().start),
            attrs: self.attributes(src, node)?,
            children: Vec::new(),
        };
        for child in node.children() {
            if child.is_text() {
                let raw = child.text().unwrap_or_default();
                let text = raw.trim_start();
                if !text.is_empty() {
                    let shown: String = text.trim_end().chars().take(20).collect();
                    let at = child.range().start + (raw.len() - text.len());
                    return Err(src
                        .loc(at)
                        .error(format!("unexpected text `{shown}` in <{}>", element.tag)));
                }
                continue;
            }
            if !child.is_element() {
                continue; // comments and processing instructions
            }
            match child.tag_name().name() {
                "default" => self.default(&src.element_only(self, child)?)?,
                "include" => {
                    let include = src.element_only(self, child)?;
                    element.children.extend(self.include(&include)?);
                }
                _ => element.children.push(self.element(src, child)?),
            }
        }
        Ok(element)
    }

    fn attributes(&self, src: &Src, node: roxmltree::Node) -> Result<Vec<Attr>, LoadError> {
        node.attributes()
            .map(|a| {
                let loc = src.loc(a.range_value().start);
                Ok(Attr {
                    name: a.name().to_string(),
                    value: self.substitute(a.value(), &loc)?,
                    loc,
                })
            })
            .collect()
    }

    /// `<default name value>`: defines `$name` unless it is defined already.
    fn default(&mut self, el: &Element) -> Result<(), LoadError> {
        el.allow_attrs(&["name", "value"])?;
        let name = el.require("name")?;
        let value = el.require("value")?;
        if name.value.is_empty() {
            return Err(name.loc.error("a <default> needs a non-empty name"));
        }
        if !self.params.iter().any(|(k, _)| *k == name.value) {
            self.params.push((name.value.clone(), value.value.clone()));
        }
        Ok(())
    }

    /// `<include filename>`: the elements it stands for.
    fn include(&mut self, el: &Element) -> Result<Vec<Element>, LoadError> {
        el.allow_attrs(&["filename"])?;
        let name = el.require("filename")?;
        let path = resolve(&self.base_dir, &name.value, self.options)
            .map_err(|message| name.loc.error(message))?;
        if !self.texts.contains_key(&path) && !path.is_file() {
            return Err(name
                .loc
                .error(format!("included file `{}` not found", path.display())));
        }
        let text = self.text(&path, Some(&el.loc))?;
        let opened = Opened {
            key: text.key.clone(),
            shown: path.clone(),
        };
        if let Some(first) = self.chain.iter().position(|o| o.key == opened.key) {
            let names: Vec<String> = self.chain[first..]
                .iter()
                .chain(std::iter::once(&opened))
                .map(|o| format!("`{}`", o.shown.display()))
                .collect();
            return Err(el
                .loc
                .error(format!("include cycle: {}", names.join(" → "))));
        }
        if self.chain.len() > MAX_INCLUDE_DEPTH {
            return Err(el.loc.error(format!(
                "includes are nested more than {MAX_INCLUDE_DEPTH} deep"
            )));
        }
        self.chain.push(opened);
        let root = self.file(&path, &text, Some(&el.loc));
        self.chain.pop();
        let root = root?;
        Ok(if root.tag == "scene" {
            root.children
        } else {
            vec![root]
        })
    }

    /// `value` with every `$name` replaced by its `<default>`; an undefined name is an error.
    fn substitute(&self, value: &str, loc: &Loc) -> Result<String, LoadError> {
        let mut out = String::with_capacity(value.len());
        let mut rest = value;
        while let Some(i) = rest.find('$') {
            out.push_str(&rest[..i]);
            let after = &rest[i + 1..];
            // Mitsuba replaces longer names first, so `$spp2` prefers `spp2` over `spp`.
            let best = self
                .params
                .iter()
                .filter(|(k, _)| after.starts_with(k.as_str()))
                .max_by_key(|(k, _)| k.len());
            let Some((k, v)) = best else {
                let name: String = after
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                return Err(loc.error(format!(
                    "`${name}` is not defined (define it with <default name=\"{name}\" value=\"…\"/> before it is used)"
                )));
            };
            let total = self.substituted.get() + v.len();
            if total > MAX_SUBSTITUTED {
                return Err(loc.error(format!(
                    "the `$name`s of this scene expand to more than {} MiB of text",
                    MAX_SUBSTITUTED >> 20
                )));
            }
            self.substituted.set(total);
            out.push_str(v);
            rest = &after[k.len()..];
        }
        out.push_str(rest);
        Ok(out)
    }
}

/// One file's text, to place byte offsets.
struct Src<'a> {
    file: &'a Rc<Path>,
    text: &'a str,
    /// Byte offset of each line's start: placing an offset is a binary search, not a scan
    /// from the file's start (which made large scenes quadratic).
    line_starts: Vec<usize>,
}

impl Src<'_> {
    fn loc(&self, offset: usize) -> Loc {
        let offset = offset.min(self.text.len());
        let line = self.line_starts.partition_point(|&s| s <= offset).max(1);
        let start = self.line_starts[line - 1];
        let (_, column) = line_column(&self.text[start..], offset - start);
        Loc {
            file: Rc::clone(self.file),
            line,
            column,
        }
    }

    /// `node`, which must have no child elements (`<default>`, `<include>`).
    fn element_only(&self, loader: &Loader, node: roxmltree::Node) -> Result<Element, LoadError> {
        let tag = node.tag_name().name().to_string();
        if let Some(child) = node.children().find(|c| c.is_element()) {
            return Err(self
                .loc(child.range().start)
                .error(format!("<{tag}> takes no child elements")));
        }
        Ok(Element {
            tag,
            loc: self.loc(node.range().start),
            attrs: loader.attributes(self, node)?,
            children: Vec::new(),
        })
    }
}

/// Mitsuba 3 reads versions 2 and 3 as written (older files need its in-memory upgrade of
/// parameter names, which lucent does not do).
fn check_version(v: &Attr) -> Result<(), LoadError> {
    let parts: Vec<&str> = v
        .value
        .split(['.', ' '])
        .filter(|s| !s.is_empty())
        .collect();
    let numbers: Option<Vec<u32>> = parts.iter().map(|p| p.parse().ok()).collect();
    let Some(numbers) = numbers.filter(|n| n.len() == 3) else {
        return Err(v.loc.error(format!(
            "cannot read the version `{}`: expected three numbers, major.minor.patch",
            v.value
        )));
    };
    if numbers[0] < 2 {
        return Err(v.loc.error(format!(
            "version {} is Mitsuba 0.x's format, whose parameter names differ; lucent reads versions 2 and 3 (load and save it with Mitsuba 3 to upgrade it)",
            v.value
        )));
    }
    Ok(())
}

/// The offset of the first start tag nested deeper than [`MAX_NESTING`], found by a scan of the
/// tags alone (comments, CDATA, processing instructions and quoted values skipped). roxmltree's
/// parser recurses once per level, so a file nested many thousands deep would overflow the stack
/// before any other check could run. On malformed text the count may be off; the parser then
/// reports the fault.
fn too_deep(text: &str) -> Option<usize> {
    let b = text.as_bytes();
    let find = |from: usize, end: &[u8]| -> usize {
        b.get(from..)
            .and_then(|rest| rest.windows(end.len()).position(|w| w == end))
            .map_or(b.len(), |i| from + i + end.len())
    };
    let mut depth = 0usize;
    let mut i = 0;
    while let Some(lt) = b
        .get(i..)
        .and_then(|rest| rest.iter().position(|&c| c == b'<'))
    {
        let start = i + lt;
        let rest = &b[start..];
        i = if rest.starts_with(b"<!--") {
            find(start + 4, b"-->")
        } else if rest.starts_with(b"<![CDATA[") {
            find(start + 9, b"]]>")
        } else if rest.starts_with(b"<?") {
            find(start + 2, b"?>")
        } else if rest.starts_with(b"</") {
            depth = depth.saturating_sub(1);
            start + 2
        } else if rest.starts_with(b"<!") {
            start + 2
        } else {
            // A start tag, to its `>` over quoted values; `/>` closes it at once.
            let mut j = start + 1;
            let mut quote = None;
            while let Some(&c) = b.get(j) {
                match quote {
                    Some(q) if c == q => quote = None,
                    Some(_) => {}
                    None if c == b'"' || c == b'\'' => quote = Some(c),
                    None if c == b'>' => break,
                    None => {}
                }
                j += 1;
            }
            if b.get(j.wrapping_sub(1)) != Some(&b'/') {
                depth += 1;
                if depth > MAX_NESTING {
                    return Some(start);
                }
            }
            j + 1
        };
    }
    None
}

/// A roxmltree error at its own position, without the position repeated in the message.
fn xml_error(path: &Path, e: &roxmltree::Error) -> LoadError {
    let pos = e.pos();
    let message = e.to_string().replace(&format!(" at {pos}"), "");
    LoadError {
        file: path.to_path_buf(),
        position: Some((pos.row as usize, pos.col as usize)),
        message: format!("malformed XML: {message}"),
    }
}

/// Test helper: the tree of `text` as if read from a file named `name` (no includes).
#[cfg(test)]
pub fn parse_str(name: &str, text: &str) -> Result<Element, LoadError> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static CALLS: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "lucent-mitsuba-xml-{}-{}",
        std::process::id(),
        CALLS.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).expect("temporary folder");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("temporary file");
    let result = load(&path, &LoadOptions::default(), &mut Fingerprint::default());
    let _ = std::fs::remove_dir_all(&dir);
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        let e = parse_str("t.xml", text).expect_err("should fail");
        format!(
            "{}:{}",
            e.position.map_or(0, |p| p.0),
            e.position.map_or(0, |p| p.1)
        ) + " "
            + &e.message
    }

    #[test]
    fn defaults_substitute_longest_name_first_and_first_definition_wins() {
        let text = "<scene version=\"3.0.0\">\n\
            <default name=\"spp\" value=\"8\"/>\n\
            <default name=\"spp2\" value=\"99\"/>\n\
            <default name=\"spp\" value=\"1\"/>\n\
            <integer name=\"a\" value=\"$spp\"/>\n\
            <integer name=\"b\" value=\"$spp2\"/>\n\
            <string name=\"c\" value=\"x$spp-$spp\"/>\n\
            </scene>";
        let root = parse_str("d.xml", text).unwrap();
        let values: Vec<&str> = root
            .children
            .iter()
            .map(|c| c.value("value").unwrap())
            .collect();
        assert_eq!(values, ["8", "99", "x8-8"]);
        assert!(root.children.iter().all(|c| c.tag != "default"));
    }

    #[test]
    fn an_undefined_name_is_an_error_at_the_value() {
        let text = "<scene version=\"3.0.0\">\n  <integer name=\"a\" value=\"$nope\"/>\n</scene>";
        let e = err(text);
        assert!(e.starts_with("2:28 `$nope` is not defined"), "{e}");
    }

    #[test]
    fn a_default_applies_only_after_it() {
        let text = "<scene version=\"3.0.0\">\n<integer name=\"a\" value=\"$n\"/>\n<default name=\"n\" value=\"1\"/>\n</scene>";
        assert!(err(text).starts_with("2:26 `$n` is not defined"));
    }

    #[test]
    fn version_is_required_and_checked() {
        assert_eq!(
            err("<scene>\n</scene>"),
            "1:1 <scene> needs a `version` attribute (e.g. version=\"3.0.0\")"
        );
        assert!(err("<scene version=\"3.0\"/>").starts_with("1:17 cannot read the version `3.0`"));
        assert!(err("<scene version=\"0.6.0\"/>").starts_with("1:17 version 0.6.0 is Mitsuba 0.x"));
        assert!(parse_str("v.xml", "<scene version=\"2.1.0\"/>").is_ok());
    }

    #[test]
    fn malformed_xml_reports_roxmltrees_position() {
        let e = parse_str(
            "m.xml",
            "<scene version=\"3.0.0\">\n  <bsdf type=\"diffuse\">\n</scene>",
        )
        .unwrap_err();
        assert_eq!(e.position, Some((3, 1)));
        assert_eq!(e.message, "malformed XML: expected 'bsdf' tag, not 'scene'");
        assert!(e.file.ends_with("m.xml"));
    }

    #[test]
    fn positions_of_elements_and_values() {
        let text = "<scene version=\"3.0.0\">\n    <float name=\"x\"  value=\"1\"/>\n</scene>";
        let root = parse_str("p.xml", text).unwrap();
        let f = &root.children[0];
        assert_eq!((f.loc.line, f.loc.column), (2, 5));
        let v = f.attr("value").unwrap();
        assert_eq!((v.loc.line, v.loc.column), (2, 29));
    }

    #[test]
    fn nesting_is_counted_over_tags_alone() {
        let nested = |n: usize| "<a>".repeat(n) + &"</a>".repeat(n);
        assert_eq!(too_deep(&nested(MAX_NESTING)), None);
        assert_eq!(too_deep(&nested(MAX_NESTING + 1)), Some(3 * MAX_NESTING));
        // Self-closing tags, comments, CDATA, instructions and quoted `>`s add no depth.
        let flat =
            "<?xml version=\"1.0\"?><a><b/><c x=\"/>\" y='>'/><!-- <d> --><![CDATA[<e>]]></a>";
        let many = flat.repeat(MAX_NESTING + 5);
        assert_eq!(too_deep(&many), None);
        assert!(too_deep("<a x=\"unclosed").is_none());
    }

    #[test]
    fn stray_text_and_wrong_root_are_errors() {
        assert!(
            err("<scene version=\"3.0.0\">\n  hello\n</scene>")
                .starts_with("2:3 unexpected text `hello`")
        );
        assert_eq!(
            err("<bsdf type=\"diffuse\"/>"),
            "1:1 the root element must be <scene>, not <bsdf>"
        );
    }
}
