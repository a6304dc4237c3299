//! The token stream as POV-Ray's parser sees it: files and macro bodies stacked, the
//! directives (`#declare`, `#if`, `#while`, `#macro`, `#include`, …) carried out as they come,
//! identifiers looked up through the scopes (a macro's or an include file's `#local`s, then
//! the global `#declare`s).

use super::lexer::{Loc, Tok, Token, tokens};
use super::scene::Defaults;
use super::value::{Macro, Value};
use crate::error::LoadError;
use crate::hash::Fingerprint;
use crate::paths::{LoadOptions, resolve};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// Deepest nesting of includes and macro calls: real scenes nest a few deep; the bound stops
/// a macro that calls itself forever.
const MAX_FRAMES: usize = 200;
/// Most loop turns and macro calls, all together: a loop whose condition never fails, or
/// macros that call themselves twice over, are an error in about a second, not a hang (a
/// turn costs about 1.6 µs). The sample scenes take at most a few hundred thousand.
const MAX_STEPS: u64 = 1_000_000;

/// Tokens being read: a file's, or a macro body's.
struct Frame {
    tokens: Rc<Vec<Token>>,
    pos: usize,
    end: usize,
    /// Whether it opened a scope of `#local`s (every file and macro body does, but the main
    /// file's is the global one).
    scoped: bool,
}

/// A block opened by a directive, closed by its `#end`.
enum Block {
    If,
    Switch,
    While {
        frame: usize,
        cond: usize,
    },
    For {
        frame: usize,
        body: usize,
        var: Rc<str>,
        to: f64,
        step: f64,
    },
}

/// The parser's state: the stacked token sources, the scopes and the open blocks.
pub struct Parser {
    frames: Vec<Frame>,
    scopes: Vec<HashMap<Rc<str>, Value>>,
    /// A macro's parameters given an identifier, by scope: `#declare` of the parameter
    /// assigns that identifier too (POV-Ray passes identifiers by reference).
    aliases: Vec<HashMap<Rc<str>, Rc<str>>>,
    blocks: Vec<(Block, usize)>,
    peeked: Option<Token>,
    last: Loc,
    /// Loop turns and macro calls so far.
    steps: u64,
    /// Folders searched for `#include`s after the scene's own.
    pub library: Vec<PathBuf>,
    base_dir: PathBuf,
    pub(super) options: LoadOptions,
    /// Bytes of every file read.
    pub inputs: Fingerprint,
    /// What was read but is not rendered as POV-Ray would, one line each.
    pub warnings: Vec<String>,
    /// `#version`'s value (3.7 unless the file says otherwise).
    pub version: f64,
    /// The first `#version` of the scene's own file (not its includes'), if any.
    pub main_version: Option<f64>,
    /// `#default`'s textures and finishes.
    pub defaults: Defaults,
    /// The image's size, for `image_width` and `image_height`.
    pub image_size: (u32, u32),
    /// The random streams `seed()` made.
    pub(super) streams: Vec<u32>,
}

impl Parser {
    /// A parser at the start of `path`.
    pub fn open(
        path: &Path,
        library: Vec<PathBuf>,
        options: &LoadOptions,
        image_size: (u32, u32),
        inputs: Fingerprint,
    ) -> Result<Self, LoadError> {
        let mut p = Self::open_empty(path, options);
        p.library = library;
        p.image_size = image_size;
        p.inputs = inputs;
        let text = std::fs::read(path)
            .map_err(|e| LoadError::file(path, format!("cannot read the file: {e}")))?;
        p.push_file(path, &text, false)?;
        Ok(p)
    }

    /// A parser of `text`, labelled `label` in errors.
    pub fn of_text(label: &Path, text: &str, options: &LoadOptions) -> Result<Self, LoadError> {
        let mut p = Self::open_empty(label, options);
        p.push_file(label, text.as_bytes(), false)?;
        Ok(p)
    }

    fn open_empty(label: &Path, options: &LoadOptions) -> Self {
        Self {
            frames: Vec::new(),
            scopes: vec![HashMap::new()],
            aliases: vec![HashMap::new()],
            blocks: Vec::new(),
            peeked: None,
            last: Loc {
                file: Rc::from(label),
                line: 1,
                column: 1,
            },
            steps: 0,
            library: Vec::new(),
            base_dir: label.parent().map_or_else(PathBuf::new, Path::to_path_buf),
            options: *options,
            inputs: Fingerprint::default(),
            warnings: Vec::new(),
            version: 3.7,
            main_version: None,
            defaults: Defaults::default(),
            image_size: (320, 240),
            streams: Vec::new(),
        }
    }

    /// Marks the next token as already read (a token given back with [`Parser::push_back`]).
    pub(super) fn peeked_is_empty(&self) -> bool {
        self.peeked.is_none()
    }

    pub(super) fn set_peeked(&mut self, t: Token) {
        self.peeked = Some(t);
    }

    fn push_file(&mut self, path: &Path, bytes: &[u8], scoped: bool) -> Result<(), LoadError> {
        self.inputs.add(bytes);
        // Scene files from old editors are often Latin-1: keep what is not UTF-8 as it is.
        let text = String::from_utf8_lossy(bytes);
        let toks = tokens(&Rc::from(path), &text)?;
        let end = toks.len();
        self.push_frame(Rc::new(toks), 0, end, scoped)
    }

    fn push_frame(
        &mut self,
        tokens: Rc<Vec<Token>>,
        pos: usize,
        end: usize,
        scoped: bool,
    ) -> Result<(), LoadError> {
        if self.frames.len() >= MAX_FRAMES {
            return Err(self.last.error(format!(
                "includes and macro calls nest more than {MAX_FRAMES} deep (a macro calling itself without end?)"
            )));
        }
        if scoped {
            self.scopes.push(HashMap::new());
            self.aliases.push(HashMap::new());
        }
        self.frames.push(Frame {
            tokens,
            pos,
            end,
            scoped,
        });
        Ok(())
    }

    /// Where the last token read was (for errors about what it began).
    pub fn loc(&self) -> Loc {
        self.last.clone()
    }

    /// A warning at `loc`, once per place and message.
    pub fn warn(&mut self, loc: &Loc, message: impl std::fmt::Display) {
        let line = loc.warning(message);
        if !self.warnings.contains(&line) {
            self.warnings.push(line);
        }
    }

    /// The next raw token of the current frames (frames that end are closed), without
    /// carrying out directives; a token looked ahead at comes first.
    fn raw(&mut self) -> Option<Token> {
        if let Some(t) = self.peeked.take() {
            self.last = t.loc.clone();
            return Some(t);
        }
        loop {
            let frame = self.frames.last_mut()?;
            if frame.pos < frame.end {
                let t = frame.tokens[frame.pos].clone();
                frame.pos += 1;
                self.last = t.loc.clone();
                return Some(t);
            }
            self.close_frame();
        }
    }

    fn close_frame(&mut self) {
        if let Some(f) = self.frames.pop()
            && f.scoped
        {
            self.scopes.pop();
            self.aliases.pop();
        }
    }

    /// The next raw token, left in place (a macro body or include that ends here stays open
    /// until that token is read: its scope is still the one assignments go to).
    fn raw_peek(&mut self) -> Option<&Token> {
        if self.peeked.is_some() {
            return self.peeked.as_ref();
        }
        self.frames
            .iter()
            .rev()
            .find(|f| f.pos < f.end)
            .map(|f| &f.tokens[f.pos])
    }

    /// Whether the next raw token (directives not carried out) is the word `w`.
    pub fn raw_peek_is_word(&mut self, w: &str) -> bool {
        self.raw_peek().is_some_and(|t| t.is_word(w))
    }

    /// The next token, directives carried out and macros called.
    pub fn next_token(&mut self) -> Result<Option<Token>, LoadError> {
        if let Some(t) = self.peeked.take() {
            self.last = t.loc.clone();
            return Ok(Some(t));
        }
        loop {
            // A directive may have looked ahead.
            if let Some(t) = self.peeked.take() {
                self.last = t.loc.clone();
                return Ok(Some(t));
            }
            let Some(t) = self.raw() else {
                if let Some((_, _)) = self.blocks.last() {
                    return Err(self.last.error(
                        "a `#if`, `#while`, `#for` or `#switch` is never closed by `#end`",
                    ));
                }
                return Ok(None);
            };
            match &t.tok {
                Tok::Directive(d) => {
                    let d = d.clone();
                    self.directive(&d, &t.loc)?;
                }
                Tok::Word(w) if matches!(self.lookup(w), Some(Value::Macro(_))) => {
                    let Some(Value::Macro(m)) = self.lookup(w).cloned() else {
                        unreachable!("looked up above");
                    };
                    self.call(&m, &t.loc)?;
                }
                _ => return Ok(Some(t)),
            }
        }
    }

    /// The next token, an error at the end of the input.
    pub fn expect_any(&mut self, what: &str) -> Result<Token, LoadError> {
        match self.next_token()? {
            Some(t) => Ok(t),
            None => Err(self
                .last
                .error(format!("the file ends where {what} was expected"))),
        }
    }

    /// The next token, left to be read.
    pub fn peek(&mut self) -> Result<Option<&Token>, LoadError> {
        if self.peeked.is_none() {
            let last = self.last.clone();
            self.peeked = self.next_token()?;
            self.last = last;
        }
        Ok(self.peeked.as_ref())
    }

    /// The next token when it is not a directive or a macro call (an expression's end is
    /// found without carrying out what follows it).
    pub fn peek_plain(&mut self) -> Option<&Token> {
        if self.peeked.is_some() {
            return self.peeked.as_ref();
        }
        let t = self.raw_peek()?;
        match &t.tok {
            Tok::Directive(_) => None,
            Tok::Word(w) => {
                let w = w.clone();
                if matches!(self.lookup(&w), Some(Value::Macro(_))) {
                    None
                } else {
                    self.raw_peek()
                }
            }
            _ => self.raw_peek(),
        }
    }

    /// Whether the next plain token is the symbol `s`; consumed when it is.
    pub fn eat_symbol(&mut self, s: &str) -> Result<bool, LoadError> {
        if self.peek_plain().is_some_and(|t| t.is_symbol(s)) {
            self.next_token()?;
            return Ok(true);
        }
        Ok(false)
    }

    /// Whether the next token (directives carried out) is the word `w`; consumed when it is.
    pub fn eat_word(&mut self, w: &str) -> Result<bool, LoadError> {
        if self.peek()?.is_some_and(|t| t.is_word(w)) {
            self.next_token()?;
            return Ok(true);
        }
        Ok(false)
    }

    /// The next word of a `{ … }` block and its token, `None` at the block's `}`; anything
    /// else is an error saying `what` was expected.
    pub fn block_word(&mut self, what: &str) -> Result<Option<(Rc<str>, Token)>, LoadError> {
        let t = self.expect_any("`}`")?;
        match &t.tok {
            Tok::Symbol("}") => Ok(None),
            Tok::Word(w) => Ok(Some((w.clone(), t))),
            _ => Err(t.loc.error(format!("expected {what}, found {}", t.tok))),
        }
    }

    /// The symbol `s`, or an error saying it was expected.
    pub fn expect_symbol(&mut self, s: &str) -> Result<(), LoadError> {
        let t = self.expect_any(&format!("`{s}`"))?;
        if t.is_symbol(s) {
            Ok(())
        } else {
            Err(t.loc.error(format!("expected `{s}`, found {}", t.tok)))
        }
    }

    /// The value the next token names, consumed, when it is an identifier whose value (an
    /// array's element, its indices read) `accept` takes; nothing is read otherwise (an array
    /// is read whole, and its element refused with an error).
    pub fn take_named(
        &mut self,
        what: &str,
        accept: impl Fn(&Value) -> bool,
    ) -> Result<Option<Value>, LoadError> {
        let Some(Token {
            tok: Tok::Word(w),
            loc,
        }) = self.peek()?.cloned()
        else {
            return Ok(None);
        };
        let value = match self.lookup(&w).cloned() {
            Some(Value::Array(a)) => {
                self.next_token()?;
                let v = self.element(&w, &a, &loc)?;
                if !accept(&v) {
                    return Err(
                        loc.error(format!("an element of `{w}` is {}, not {what}", v.kind()))
                    );
                }
                return Ok(Some(v));
            }
            Some(v) if accept(&v) => v,
            _ => return Ok(None),
        };
        self.next_token()?;
        Ok(Some(value))
    }

    /// The indices `[i][j]…` that follow an array's name (none: an empty list).
    pub fn indices(&mut self) -> Result<Vec<f64>, LoadError> {
        let mut index = Vec::new();
        while self.eat_symbol("[")? {
            index.push(self.float()?);
            self.expect_symbol("]")?;
        }
        Ok(index)
    }

    /// The element of array `a` (named `name`) that the indices next name, which must be set.
    pub fn element(
        &mut self,
        name: &str,
        a: &std::cell::RefCell<super::value::Array>,
        loc: &Loc,
    ) -> Result<Value, LoadError> {
        let index = self.indices()?;
        let a = a.borrow();
        let at = a.flat_index(&index).ok_or_else(|| {
            loc.error(format!(
                "index {index:?} is outside `{name}` of size {:?}",
                a.dims
            ))
        })?;
        a.items[at]
            .clone()
            .ok_or_else(|| loc.error(format!("`{name}{index:?}` is not set")))
    }

    /// An identifier's value, innermost scope first.
    pub fn lookup(&self, name: &str) -> Option<&Value> {
        self.scopes.iter().rev().find_map(|s| s.get(name))
    }

    /// Sets `name` in the global scope (`#declare`) or the innermost (`#local`).
    pub fn set(&mut self, name: Rc<str>, value: Value, local: bool) {
        if !local {
            // POV-Ray: `#declare` of a name local somewhere assigns the innermost such; a
            // macro's parameter given an identifier assigns that identifier too.
            if let Some(i) = self.scopes.iter().rposition(|s| s.contains_key(&name)) {
                let target = self.aliases[i].get(&name).cloned();
                self.scopes[i].insert(name, value.clone());
                if let Some(target) = target {
                    let below = &mut self.scopes[..i];
                    if let Some(scope) = below.iter_mut().rev().find(|s| s.contains_key(&target)) {
                        scope.insert(target, value);
                    }
                }
                return;
            }
            self.scopes[0].insert(name, value);
        } else if let Some(scope) = self.scopes.last_mut() {
            scope.insert(name, value);
        }
    }

    /// Carries out the directive `#d`.
    fn directive(&mut self, d: &str, loc: &Loc) -> Result<(), LoadError> {
        match d {
            "declare" | "local" => self.declare(d == "local", loc),
            "undef" => {
                let name = self.raw_name(loc)?;
                for s in &mut self.scopes {
                    s.remove(&name);
                }
                Ok(())
            }
            "include" => self.include(loc),
            "if" => {
                let c = self.condition()?;
                self.branch(c)
            }
            "ifdef" | "ifndef" => {
                self.expect_symbol("(")?;
                let name = self.raw_name(loc)?;
                let mut defined = self.lookup(&name).is_some();
                // `#ifdef(A[3])`: whether that element is set.
                if self.eat_symbol("[")? {
                    let i = self.float()?;
                    self.expect_symbol("]")?;
                    defined = matches!(self.lookup(&name), Some(Value::Array(a))
                        if a.borrow().items.get(i as usize).is_some_and(Option::is_some));
                }
                self.expect_symbol(")")?;
                self.branch(defined == (d == "ifdef"))
            }
            "else" | "elseif" => match self.blocks.last() {
                Some((Block::If, _)) => {
                    self.skip_block(loc)?;
                    self.blocks.pop();
                    Ok(())
                }
                Some((Block::Switch, _)) => {
                    self.skip_block(loc)?;
                    self.blocks.pop();
                    Ok(())
                }
                _ => Err(loc.error(format!("`#{d}` without its `#if`"))),
            },
            "while" => {
                let frame = self.frames.len();
                let cond = self.frames.last().map_or(0, |f| f.pos);
                if self.condition()? {
                    self.blocks.push((Block::While { frame, cond }, frame));
                } else {
                    self.skip_block(loc)?;
                }
                Ok(())
            }
            "for" => self.for_loop(loc),
            "switch" => self.switch(loc),
            "case" | "range" => match self.blocks.last() {
                // Falling through from the clause before.
                Some((Block::Switch, _)) => {
                    self.expect_symbol("(")?;
                    self.float()?;
                    if d == "range" {
                        self.eat_symbol(",")?;
                        self.float()?;
                    }
                    self.expect_symbol(")")?;
                    Ok(())
                }
                _ => Err(loc.error(format!("`#{d}` outside a `#switch`"))),
            },
            "break" => match self.blocks.last() {
                Some(_) => {
                    self.skip_block(loc)?;
                    self.blocks.pop();
                    Ok(())
                }
                None => Err(loc.error("`#break` outside a `#switch` or loop")),
            },
            "end" => self.end(loc),
            "macro" => self.define_macro(loc),
            "version" => {
                self.version = self.float()?;
                if self.frames.len() == 1 && self.main_version.is_none() {
                    self.main_version = Some(self.version);
                }
                self.eat_symbol(";")?;
                Ok(())
            }
            "debug" | "warning" => {
                self.string()?;
                Ok(())
            }
            "error" => {
                let message = self.string()?;
                Err(loc.error(format!("the scene stops with `#error`: {message}")))
            }
            "default" => self.default_block(),
            "fopen" | "fclose" | "read" | "write" => Err(loc.error(format!(
                "`#{d}`: lucent does not read or write files from a scene"
            ))),
            _ => Err(loc.error(format!("`#{d}` is not a POV-Ray 3.7 directive"))),
        }
    }

    /// An identifier after a directive, read as it stands (not looked up or called).
    fn raw_name(&mut self, loc: &Loc) -> Result<Rc<str>, LoadError> {
        match self.raw() {
            Some(Token {
                tok: Tok::Word(w), ..
            }) => Ok(w),
            Some(t) => Err(t
                .loc
                .error(format!("expected an identifier, found {}", t.tok))),
            None => Err(loc.error("the file ends where an identifier was expected")),
        }
    }

    fn declare(&mut self, local: bool, loc: &Loc) -> Result<(), LoadError> {
        let mut name = self.raw_name(loc)?;
        // `#declare deprecated [once] "message" Name = …`.
        if &*name == "deprecated" {
            if self.raw_peek_is_word("once") {
                self.raw();
            }
            self.string()?;
            name = self.raw_name(loc)?;
        }
        if is_reserved(&name) {
            return Err(self.last.error(format!(
                "`{name}` is a POV-Ray keyword, not a name to declare"
            )));
        }
        // An array element: `#declare A[i][j] = …`.
        let index = self.indices()?;
        self.expect_symbol("=")?;
        let value = self.declared_value()?;
        // The `;` after a number, vector or string (optional after an object).
        if self.raw_peek().is_some_and(|t| t.is_symbol(";")) {
            self.raw();
        }
        if index.is_empty() {
            self.set(name, value, local);
            return Ok(());
        }
        let Some(Value::Array(a)) = self.lookup(&name) else {
            return Err(loc.error(format!("`{name}` is not an array")));
        };
        let mut a = a.borrow_mut();
        let at = a.flat_index(&index).ok_or_else(|| {
            loc.error(format!(
                "index {index:?} is outside the array `{name}` of size {:?}",
                a.dims
            ))
        })?;
        a.items[at] = Some(value);
        Ok(())
    }

    fn include(&mut self, loc: &Loc) -> Result<(), LoadError> {
        let name = self.string()?;
        let mut found = None;
        let mut folders = vec![self.base_dir.clone()];
        folders.extend(self.library.iter().cloned());
        for folder in &folders {
            let path = if folder == &self.base_dir {
                resolve(folder, &name, &self.options).map_err(|m| loc.error(m))?
            } else {
                folder.join(&*name)
            };
            if path.is_file() {
                found = Some(path);
                break;
            }
        }
        let Some(path) = found else {
            return Err(loc.error(format!(
                "the include file \"{name}\" is not in the scene's folder or the library path ({}); give POV-Ray's include folder with --povray-library",
                self.library
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        };
        let bytes = std::fs::read(&path)
            .map_err(|e| loc.error(format!("cannot read \"{}\": {e}", path.display())))?;
        self.push_file(&path, &bytes, true)
    }

    /// `( expression )` as a truth value.
    fn condition(&mut self) -> Result<bool, LoadError> {
        let v = self.float()?;
        Ok(v != 0.0)
    }

    fn branch(&mut self, taken: bool) -> Result<(), LoadError> {
        let frame = self.frames.len();
        if taken {
            self.blocks.push((Block::If, frame));
            return Ok(());
        }
        let loc = self.last.clone();
        // To the `#else`, a true `#elseif`, or the `#end`.
        loop {
            match self.skip_to_clause(&loc)?.as_ref() {
                "else" => {
                    self.blocks.push((Block::If, frame));
                    return Ok(());
                }
                "elseif" => {
                    if self.condition()? {
                        self.blocks.push((Block::If, frame));
                        return Ok(());
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    /// Skips to the next `#else`, `#elseif`, `#case`, `#range`, `#break` or `#end` of this
    /// block (nested blocks skipped whole) and says which it was.
    fn skip_to_clause(&mut self, loc: &Loc) -> Result<Rc<str>, LoadError> {
        let mut depth = 0usize;
        let depth_of_frames = self.frames.len();
        loop {
            if self.frames.len() < depth_of_frames {
                return Err(loc.error("this block is never closed by `#end` in its file"));
            }
            let Some(t) = self.raw() else {
                return Err(loc.error("this block is never closed by `#end`"));
            };
            if let Tok::Directive(d) = &t.tok {
                match &**d {
                    "if" | "ifdef" | "ifndef" | "while" | "for" | "switch" | "macro" => depth += 1,
                    "end" if depth > 0 => depth -= 1,
                    "end" | "else" | "elseif" | "case" | "range" | "break" if depth == 0 => {
                        return Ok(d.clone());
                    }
                    _ => {}
                }
            }
        }
    }

    /// Skips to this block's `#end`, past it.
    fn skip_block(&mut self, loc: &Loc) -> Result<(), LoadError> {
        while &*self.skip_to_clause(loc)? != "end" {}
        Ok(())
    }

    fn for_loop(&mut self, loc: &Loc) -> Result<(), LoadError> {
        self.expect_symbol("(")?;
        let var = self.raw_name(loc)?;
        self.expect_symbol(",")?;
        let from = self.float()?;
        self.expect_symbol(",")?;
        let to = self.float()?;
        let step = if self.eat_symbol(",")? {
            self.float()?
        } else {
            1.0
        };
        self.expect_symbol(")")?;
        if step == 0.0 {
            return Err(loc.error("a `#for` loop's step is 0"));
        }
        self.set(var.clone(), Value::Float(from), false);
        if (step > 0.0 && from > to) || (step < 0.0 && from < to) {
            return self.skip_block(loc);
        }
        let frame = self.frames.len();
        let body = self.frames.last().map_or(0, |f| f.pos);
        self.push_for(frame, body, var, to, step);
        Ok(())
    }

    fn switch(&mut self, loc: &Loc) -> Result<(), LoadError> {
        let value = self.float()?;
        let frame = self.frames.len();
        loop {
            let clause = self.skip_to_clause(loc)?;
            match &*clause {
                "case" => {
                    let v = self.float()?;
                    if v == value {
                        break;
                    }
                }
                "range" => {
                    self.expect_symbol("(")?;
                    let lo = self.float()?;
                    self.eat_symbol(",")?;
                    let hi = self.float()?;
                    self.expect_symbol(")")?;
                    if (lo..=hi).contains(&value) {
                        break;
                    }
                }
                "else" => break,
                "end" => return Ok(()),
                _ => {}
            }
        }
        self.blocks.push((Block::Switch, frame));
        Ok(())
    }

    fn end(&mut self, loc: &Loc) -> Result<(), LoadError> {
        let Some((block, _)) = self.blocks.pop() else {
            return Err(loc.error("`#end` without a block to close"));
        };
        match block {
            Block::If | Block::Switch => Ok(()),
            Block::While { frame, cond } => {
                self.turn(loc)?;
                self.jump(frame, cond, loc)?;
                if self.condition()? {
                    self.blocks.push((Block::While { frame, cond }, frame));
                    Ok(())
                } else {
                    self.skip_block(loc)
                }
            }
            Block::For {
                frame,
                body,
                var,
                to,
                step,
            } => {
                self.turn(loc)?;
                let Some(Value::Float(i)) = self.lookup(&var).cloned() else {
                    return Err(
                        loc.error(format!("the loop's variable `{var}` is no longer a number"))
                    );
                };
                let i = i + step;
                self.set(var.clone(), Value::Float(i), false);
                if (step > 0.0 && i <= to) || (step < 0.0 && i >= to) {
                    self.jump(frame, body, loc)?;
                    self.push_for(frame, body, var, to, step);
                }
                Ok(())
            }
        }
    }

    /// Opens a `#for` loop's block: its body starts at `body` in frame `frame`.
    fn push_for(&mut self, frame: usize, body: usize, var: Rc<str>, to: f64, step: f64) {
        let block = Block::For {
            frame,
            body,
            var,
            to,
            step,
        };
        self.blocks.push((block, frame));
    }

    fn turn(&mut self, loc: &Loc) -> Result<(), LoadError> {
        self.steps += 1;
        if self.steps > MAX_STEPS {
            return Err(loc.error(format!(
                "loops and macro calls have run more than {MAX_STEPS} times: a loop whose condition never fails, or a macro calling itself without end?"
            )));
        }
        Ok(())
    }

    fn jump(&mut self, frame: usize, pos: usize, loc: &Loc) -> Result<(), LoadError> {
        if self.frames.len() != frame {
            return Err(loc.error("a loop's `#end` is in another file or macro than its start"));
        }
        if let Some(f) = self.frames.last_mut() {
            f.pos = pos;
        }
        Ok(())
    }

    fn define_macro(&mut self, loc: &Loc) -> Result<(), LoadError> {
        let name = self.raw_name(loc)?;
        self.expect_symbol("(")?;
        let mut params = Vec::new();
        loop {
            match self.raw() {
                Some(t) if t.is_symbol(")") => break,
                Some(t) if t.is_symbol(",") => {}
                Some(Token {
                    tok: Tok::Word(w), ..
                }) => params.push(w),
                Some(t) => {
                    return Err(t
                        .loc
                        .error(format!("expected a parameter's name, found {}", t.tok)));
                }
                None => return Err(loc.error("the file ends in a macro's parameters")),
            }
        }
        let frame = self
            .frames
            .last()
            .ok_or_else(|| loc.error("a macro outside a file"))?;
        let tokens = frame.tokens.clone();
        let start = frame.pos;
        let depth = self.frames.len();
        self.skip_block(loc)?;
        if self.frames.len() != depth {
            return Err(loc.error("this macro's `#end` is not in its file"));
        }
        let end = self.frames.last().map_or(0, |f| f.pos) - 1;
        let m = Macro {
            params,
            tokens,
            body: (start, end),
            loc: loc.clone(),
        };
        self.set(name, Value::Macro(Rc::new(m)), false);
        Ok(())
    }

    /// Calls macro `m`: its arguments bound to its parameters in a new scope, its body read
    /// next.
    fn call(&mut self, m: &Rc<Macro>, loc: &Loc) -> Result<(), LoadError> {
        self.expect_symbol("(")?;
        let mut args = Vec::new();
        let mut by_name = Vec::new();
        if !self.eat_symbol(")")? {
            loop {
                by_name.push(self.lone_identifier()?);
                args.push(self.declared_value()?);
                if self.eat_symbol(")")? {
                    break;
                }
                self.expect_symbol(",")?;
            }
        }
        if args.len() != m.params.len() {
            return Err(loc.error(format!(
                "the macro declared at {} takes {} arguments, given {}",
                m.loc,
                m.params.len(),
                args.len()
            )));
        }
        self.turn(loc)?;
        self.push_frame(m.tokens.clone(), m.body.0, m.body.1, true)?;
        let scope = self.scopes.last_mut().expect("pushed above");
        for (p, a) in m.params.iter().zip(args) {
            scope.insert(p.clone(), a);
        }
        let aliases = self.aliases.last_mut().expect("pushed above");
        for (p, name) in m.params.iter().zip(by_name) {
            if let Some(name) = name {
                aliases.insert(p.clone(), name);
            }
        }
        Ok(())
    }

    /// The identifier a macro's argument is, when it is one alone (`M(Thing, 2)`), left to
    /// be read.
    fn lone_identifier(&mut self) -> Result<Option<Rc<str>>, LoadError> {
        let Some(Token {
            tok: Tok::Word(w), ..
        }) = self.peek()?.cloned()
        else {
            return Ok(None);
        };
        if self.lookup(&w).is_none() {
            return Ok(None);
        }
        let t = self.next_token()?.expect("peeked");
        let alone = self
            .peek_plain()
            .is_some_and(|n| n.is_symbol(",") || n.is_symbol(")"));
        self.push_back(t);
        Ok(alone.then_some(w))
    }
}

/// Words that cannot be declared (the language's own, a short list of the common ones).
fn is_reserved(name: &str) -> bool {
    matches!(
        name,
        "sphere"
            | "box"
            | "plane"
            | "union"
            | "object"
            | "texture"
            | "pigment"
            | "finish"
            | "camera"
            | "light_source"
            | "x"
            | "y"
            | "z"
            | "pi"
            | "rgb"
            | "color"
            | "colour"
    )
}

impl super::value::Array {
    /// The flat index of element `index`, if inside.
    pub fn flat_index(&self, index: &[f64]) -> Option<usize> {
        if index.len() != self.dims.len() {
            return None;
        }
        let mut at = 0usize;
        for (i, d) in index.iter().zip(&self.dims) {
            if *i < 0.0 || *i as usize >= *d {
                return None;
            }
            at = at * d + *i as usize;
        }
        Some(at)
    }
}
