//! The HTML of the report: a page with its style and a small check script, sections,
//! tables, figures. Everything is inline: the page loads nothing from anywhere.

use crate::plot::shape::escape;

/// The script at the top of the page: a script error or a console error puts `EOM-ERROR`
/// into the title (where a headless browser's `--dump-dom` shows it); after loading, every
/// `<svg>` whose drawn content has no extent is counted into `data-empty-svgs` of `<html>`,
/// text outside its figure, text over other text and headings or LaTeX cut off into
/// `data-text-outside`, `data-text-overlaps` and `data-text-clipped` (the first few named in
/// `data-text-problems`), and `data-rendered` is set.
const CHECK_SCRIPT: &str = r#"<script>
(function () {
  var errors = [];
  function fail(m) { errors.push(String(m)); document.title = 'EOM-ERROR: ' + errors.join(' | '); }
  window.addEventListener('error', function (e) { fail(e.message || 'resource error'); }, true);
  window.addEventListener('unhandledrejection', function (e) { fail(e.reason); });
  var ce = console.error;
  console.error = function () { fail(Array.prototype.join.call(arguments, ' ')); ce.apply(console, arguments); };
  window.addEventListener('load', function () {
    var empty = 0, svgs = document.querySelectorAll('figure > svg');
    for (var i = 0; i < svgs.length; i++) {
      var b = svgs[i].getBBox();
      if (!(b.width > 0 && b.height > 0) || svgs[i].querySelectorAll('line,polyline,path,circle,rect').length === 0) { empty++; }
    }
    // Geometry: text outside its picture, text over other text in a picture, and text the
    // page cuts off (headings, the LaTeX beside formulas); a few of each named.
    var outside = 0, overlaps = 0, clipped = 0, named = [];
    function name(m) { if (named.length < 8) { named.push(m); } }
    for (var i = 0; i < svgs.length; i++) {
      var s = svgs[i], vb = s.viewBox.baseVal, inv = s.getScreenCTM().inverse(), boxes = [];
      var texts = s.querySelectorAll('text');
      for (var k = 0; k < texts.length; k++) {
        var t = texts[k], b = t.getBBox(), m = inv.multiply(t.getScreenCTM());
        if (!(b.width > 0) || t.textContent.trim() === '') { continue; }
        var p = [[b.x, b.y], [b.x + b.width, b.y + b.height]].map(function (q) {
          var pt = s.createSVGPoint(); pt.x = q[0]; pt.y = q[1]; return pt.matrixTransform(m); });
        var x0 = Math.min(p[0].x, p[1].x), x1 = Math.max(p[0].x, p[1].x);
        var y0 = Math.min(p[0].y, p[1].y), y1 = Math.max(p[0].y, p[1].y);
        var label = 'figure ' + (i + 1) + ' "' + t.textContent.trim().slice(0, 40) + '"';
        if (x0 < vb.x - 1 || y0 < vb.y - 1 || x1 > vb.x + vb.width + 1 || y1 > vb.y + vb.height + 1) {
          outside++; name(label + ' outside');
        }
        for (var j = 0; j < boxes.length; j++) {
          var o = boxes[j];
          var same = o[4] === t.textContent.trim() && Math.abs(o[0] - x0) < 1 && Math.abs(o[1] - y0) < 1;
          if (!same && Math.min(o[2], x1) - Math.max(o[0], x0) > 1 && Math.min(o[3], y1) - Math.max(o[1], y0) > 1) {
            overlaps++; name(label + ' over "' + o[4].slice(0, 40) + '"');
          }
        }
        boxes.push([x0, y0, x1, y1, t.textContent.trim()]);
      }
    }
    var cut = document.querySelectorAll('h1, h2, .formula pre');
    for (var i = 0; i < cut.length; i++) {
      if (cut[i].scrollWidth > cut[i].clientWidth + 1) { clipped++; name(cut[i].tagName + ' cut off'); }
    }
    document.documentElement.setAttribute('data-text-outside', String(outside));
    document.documentElement.setAttribute('data-text-overlaps', String(overlaps));
    document.documentElement.setAttribute('data-text-clipped', String(clipped));
    document.documentElement.setAttribute('data-text-problems', named.join('; '));
    document.documentElement.setAttribute('data-figures', String(svgs.length));
    document.documentElement.setAttribute('data-empty-svgs', String(empty));
    document.documentElement.setAttribute('data-rendered', errors.length ? 'with-errors' : 'yes');
  });
})();
</script>"#;

const STYLE: &str = r#"<style>
body { font-family: sans-serif; max-width: 1180px; margin: 1em auto; padding: 0 1em; color: #222; }
h1 { font-size: 1.7em; overflow-wrap: anywhere; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; overflow-wrap: anywhere; }
table { border-collapse: collapse; margin: 0.6em 0; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.6em; text-align: right; }
th { background: #f2f2f2; } td.l, th.l { text-align: left; }
figure { margin: 1em 0; } figure > svg { max-width: 100%; height: auto; border: 1px solid #eee; }
figcaption { color: #555; font-size: 0.9em; }
.formula { display: flex; gap: 1.5em; align-items: center; flex-wrap: wrap; margin: 0.6em 0; }
.formula pre { background: #f6f6f6; padding: 0.4em; max-width: 520px; white-space: pre-wrap; overflow-wrap: anywhere; font-size: 0.8em; }
.formula > div { max-width: 100%; overflow-wrap: anywhere; }
.note { color: #8a3b00; } nav a { margin-right: 0.8em; }
</style>"#;

/// A page being written.
#[derive(Default)]
pub struct Page {
    body: String,
    toc: Vec<(String, String)>,
}

impl Page {
    /// Starts a section with a heading (and an entry in the contents).
    pub fn section(&mut self, id: &str, title: &str) {
        self.toc.push((id.to_string(), title.to_string()));
        self.body.push_str(&format!(
            "<h2 id=\"{}\">{}</h2>\n",
            escape(id),
            escape(title)
        ));
    }

    /// A paragraph of plain text.
    pub fn text(&mut self, t: &str) {
        self.body.push_str(&format!("<p>{}</p>\n", escape(t)));
    }

    /// A note (warning) paragraph.
    pub fn note(&mut self, t: &str) {
        self.body
            .push_str(&format!("<p class=\"note\">{}</p>\n", escape(t)));
    }

    /// A table: the first `left` columns left-aligned (names), the others right-aligned.
    pub fn table(&mut self, head: &[&str], rows: &[Vec<String>], left: usize) {
        let cls = |k: usize| if k < left { " class=\"l\"" } else { "" };
        let mut t = String::from("<table><tr>");
        for (k, h) in head.iter().enumerate() {
            t.push_str(&format!("<th{}>{}</th>", cls(k), escape(h)));
        }
        t.push_str("</tr>\n");
        for r in rows {
            t.push_str("<tr>");
            for (k, c) in r.iter().enumerate() {
                t.push_str(&format!("<td{}>{}</td>", cls(k), escape(c)));
            }
            t.push_str("</tr>\n");
        }
        t.push_str("</table>\n");
        self.body.push_str(&t);
    }

    /// A figure: an SVG document inline, with a caption.
    pub fn figure(&mut self, svg: &str, caption: &str) {
        // The XML declaration (if any) is not allowed inside HTML.
        let svg = svg
            .trim_start()
            .strip_prefix("<?xml")
            .and_then(|r| r.find("?>").map(|i| &r[i + 2..]))
            .unwrap_or(svg);
        self.body.push_str(&format!(
            "<figure>{}<figcaption>{}</figcaption></figure>\n",
            svg.trim(),
            escape(caption)
        ));
    }

    /// A formula: MathML (inner content) with its LaTeX beside it for copying.
    pub fn formula(&mut self, label: &str, mathml: &str, latex: &str) {
        self.body.push_str(&format!(
            "<div class=\"formula\"><div>{}</div>{}<pre>{}</pre></div>\n",
            escape(label),
            super::mathml::block(mathml),
            escape(latex)
        ));
    }

    /// Writes one part of the page by `make`; when it fails, whatever it wrote is taken back
    /// and the part is a section `id` with its `title` saying why it could not be made, so
    /// that one part that cannot be made never costs the whole page.
    pub fn part<E: std::fmt::Display>(
        &mut self,
        id: &str,
        title: &str,
        make: impl FnOnce(&mut Page) -> Result<(), E>,
    ) {
        let (body, toc) = (self.body.len(), self.toc.len());
        if let Err(e) = make(self) {
            self.body.truncate(body);
            self.toc.truncate(toc);
            self.section(id, title);
            self.note(&format!("This part could not be made: {e}"));
        }
    }

    /// The whole document.
    pub fn finish(self, title: &str, intro: &str) -> String {
        let toc: String = self
            .toc
            .iter()
            .map(|(id, t)| format!("<a href=\"#{}\">{}</a>", escape(id), escape(t)))
            .collect();
        format!(
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
             <title>{t}</title>{CHECK_SCRIPT}{STYLE}</head>\n<body>\n<h1>{t}</h1>\n<p>{}</p>\n\
             <nav>{toc}</nav>\n{}\n</body></html>\n",
            escape(intro),
            self.body,
            t = escape(title),
        )
    }
}
