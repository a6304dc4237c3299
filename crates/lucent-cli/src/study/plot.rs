//! A small SVG line chart: enough for the study's two plots, without a plotting library.

use std::fmt::Write;

/// One line of a chart.
pub struct Series {
    /// Legend text.
    pub name: String,
    /// CSS colour.
    pub color: &'static str,
    /// Dashed (reference lines).
    pub dashed: bool,
    /// Points, in data units.
    pub points: Vec<(f64, f64)>,
}

/// A chart's axes.
pub struct Chart<'a> {
    /// Title above the plot.
    pub title: &'a str,
    /// Axis labels.
    pub x_label: &'a str,
    /// Axis labels.
    pub y_label: &'a str,
    /// Logarithmic x axis (base 2 ticks).
    pub log_x: bool,
    /// The lines.
    pub series: Vec<Series>,
}

const W: f64 = 760.0;
const H: f64 = 330.0;
const LEFT: f64 = 70.0;
const RIGHT: f64 = 170.0;
const TOP: f64 = 36.0;
const BOTTOM: f64 = 46.0;

/// Charts stacked in one SVG document.
pub fn svg(charts: &[Chart]) -> String {
    let mut out = String::new();
    let height = H * charts.len() as f64;
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{height}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#);
    for (i, chart) in charts.iter().enumerate() {
        let _ = writeln!(out, r#"<g transform="translate(0,{})">"#, i as f64 * H);
        draw(&mut out, chart);
        let _ = writeln!(out, "</g>");
    }
    out.push_str("</svg>\n");
    out
}

fn draw(out: &mut String, c: &Chart) {
    let fx = |x: f64| if c.log_x { x.log2() } else { x };
    let points = c.series.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64);
    for &(x, y) in points.filter(|p| p.0.is_finite() && p.1.is_finite()) {
        x0 = x0.min(fx(x));
        x1 = x1.max(fx(x));
        y1 = y1.max(y);
    }
    if x0.partial_cmp(&x1) != Some(std::cmp::Ordering::Less) {
        (x0, x1) = (x0.min(0.0), x0.max(0.0) + 1.0);
    }
    let y1 = if y1 > 0.0 { nice_ceiling(y1) } else { 1.0 };
    let (pw, ph) = (W - LEFT - RIGHT, H - TOP - BOTTOM);
    let sx = |x: f64| LEFT + (fx(x) - x0) / (x1 - x0) * pw;
    let sy = |y: f64| TOP + ph - y / y1 * ph;
    let _ = writeln!(
        out,
        r#"<text x="{}" y="20" font-size="14" text-anchor="middle">{}</text>"#,
        LEFT + pw / 2.0,
        escape(c.title)
    );
    let _ = writeln!(
        out,
        r##"<rect x="{LEFT}" y="{TOP}" width="{pw}" height="{ph}" fill="none" stroke="#444"/>"##
    );
    for k in 0..=5 {
        let y = y1 * f64::from(k) / 5.0;
        let (right, at, label_x) = (LEFT + pw, sy(y), LEFT - 6.0);
        let _ = writeln!(
            out,
            r##"<line x1="{LEFT}" x2="{right}" y1="{at}" y2="{at}" stroke="#ddd"/><text x="{label_x}" y="{}" text-anchor="end">{}</text>"##,
            at + 4.0,
            short(y)
        );
    }
    for k in 0..=6 {
        let v = x0 + (x1 - x0) * f64::from(k) / 6.0;
        let label = if c.log_x { short(v.exp2()) } else { short(v) };
        let x = LEFT + (v - x0) / (x1 - x0) * pw;
        let _ = writeln!(
            out,
            r#"<text x="{x}" y="{}" text-anchor="middle">{label}</text>"#,
            TOP + ph + 16.0
        );
    }
    let _ = writeln!(
        out,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        LEFT + pw / 2.0,
        H - 8.0,
        escape(c.x_label)
    );
    let _ = writeln!(
        out,
        r#"<text transform="translate(16,{}) rotate(-90)" text-anchor="middle">{}</text>"#,
        TOP + ph / 2.0,
        escape(c.y_label)
    );
    for (i, s) in c.series.iter().enumerate() {
        let path: Vec<String> = s
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|&(x, y)| format!("{:.1},{:.1}", sx(x), sy(y)))
            .collect();
        let dash = if s.dashed {
            r#" stroke-dasharray="6,4""#
        } else {
            ""
        };
        let _ = writeln!(
            out,
            r#"<polyline fill="none" stroke="{}" stroke-width="1.6"{dash} points="{}"/>"#,
            s.color,
            path.join(" ")
        );
        let ly = TOP + 14.0 + 18.0 * i as f64;
        let lx = LEFT + pw + 12.0;
        let _ = writeln!(
            out,
            r#"<line x1="{lx}" x2="{}" y1="{ly}" y2="{ly}" stroke="{}" stroke-width="2"{dash}/><text x="{}" y="{}">{}</text>"#,
            lx + 22.0,
            s.color,
            lx + 28.0,
            ly + 4.0,
            escape(&s.name)
        );
    }
}

/// The smallest of 1, 2, 2.5, 5 times a power of ten at or above `v`.
fn nice_ceiling(v: f64) -> f64 {
    let p = 10f64.powf(v.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&c| c >= v)
        .unwrap_or(10.0 * p)
}

fn short(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 10_000.0 {
        format!("{:.0}k", v / 1000.0)
    } else if v.abs() >= 10.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.3}")
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string()
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chart_has_one_line_per_series_and_a_legend() {
        let chart = Chart {
            title: "t <1>",
            x_label: "x",
            y_label: "y",
            log_x: true,
            series: vec![
                Series {
                    name: "a".into(),
                    color: "red",
                    dashed: false,
                    points: vec![(1.0, 0.5), (4.0, 0.25)],
                },
                Series {
                    name: "b".into(),
                    color: "blue",
                    dashed: true,
                    points: vec![(1.0, 0.1), (8.0, 0.3)],
                },
            ],
        };
        let s = svg(&[chart]);
        assert_eq!(s.matches("<polyline").count(), 2);
        assert!(s.contains("t &lt;1&gt;") && s.contains("stroke-dasharray"));
        assert_eq!(nice_ceiling(0.37), 0.5);
        assert_eq!(short(0.25), "0.25");
    }
}
