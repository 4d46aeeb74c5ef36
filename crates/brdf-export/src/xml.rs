//! A small element tree written with quick-xml (attribute escaping,
//! indentation), shared by the Mitsuba and MaterialX writers.

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, BytesText, Event};

/// An XML element with attributes and children.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Node {
    tag: String,
    attrs: Vec<(String, String)>,
    children: Vec<Node>,
}

impl Node {
    pub(crate) fn new(tag: &str) -> Self {
        Node {
            tag: tag.to_string(),
            attrs: Vec::new(),
            children: Vec::new(),
        }
    }

    pub(crate) fn attr(mut self, k: &str, v: impl ToString) -> Self {
        self.attrs.push((k.to_string(), v.to_string()));
        self
    }

    pub(crate) fn child(mut self, c: Node) -> Self {
        self.children.push(c);
        self
    }

    /// The element's tag.
    pub(crate) fn tag(&self) -> &str {
        &self.tag
    }

    /// The value of attribute `k`, if set.
    pub(crate) fn get(&self, k: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(key, _)| key == k)
            .map(|(_, v)| v.as_str())
    }

    /// The child elements, in order.
    pub(crate) fn children(&self) -> &[Node] {
        &self.children
    }

    /// The `name` attribute ("" when there is none).
    pub(crate) fn name(&self) -> &str {
        self.get("name").unwrap_or("")
    }

    /// This element with `other`'s attributes and children appended.
    pub(crate) fn attr_from(mut self, other: &Node) -> Self {
        self.attrs.extend(other.attrs.iter().cloned());
        self.children.extend(other.children.iter().cloned());
        self
    }

    fn write<W: std::io::Write>(&self, w: &mut Writer<W>) -> std::io::Result<()> {
        let mut start = BytesStart::new(self.tag.as_str());
        for (k, v) in &self.attrs {
            start.push_attribute((k.as_str(), v.as_str()));
        }
        if self.children.is_empty() {
            w.write_event(Event::Empty(start))?;
        } else {
            w.write_event(Event::Start(start))?;
            for c in &self.children {
                c.write(w)?;
            }
            w.write_event(Event::End(BytesEnd::new(self.tag.as_str())))?;
        }
        Ok(())
    }

    /// The document text, with an XML declaration when `decl` and `comment`
    /// before the root element.
    pub(crate) fn to_document(&self, decl: bool, comment: Option<&str>) -> String {
        let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
        // Writing into a Vec cannot fail.
        if decl {
            let _ = w.write_event(Event::Decl(BytesDecl::new("1.0", Some("utf-8"), None)));
        }
        if let Some(c) = comment {
            // XML forbids `--` inside a comment.
            let text = format!(" {} ", c.replace("--", "- -"));
            let _ = w.write_event(Event::Comment(BytesText::from_escaped(text)));
        }
        let _ = self.write(&mut w);
        let mut s = String::from_utf8_lossy(&w.into_inner()).into_owned();
        s.push('\n');
        s
    }
}
