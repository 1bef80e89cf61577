#include "svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace {

constexpr double kW = 640, kH = 420, kLeft = 70, kRight = 150, kTop = 40, kBottom = 50;
const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"};

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
}

std::string tick(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, v >= 1 ? "%.0f" : "%g", v);
    return buf;
}

}  // namespace

SvgPlot::SvgPlot(std::string title, std::string x_label, std::string y_label, std::string labels)
    : title_(std::move(title)),
      x_label_(std::move(x_label)),
      y_label_(std::move(y_label)),
      labels_(std::move(labels)) {}

void SvgPlot::add_series(const std::string& name, const std::vector<Point>& points) {
    series_.push_back({name, points});
}

std::string SvgPlot::render() const {
    // Log axes from the decade below the smallest positive value to the one above the
    // largest; a zero is drawn on the bottom (or left) edge, a decade under every other value.
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const Series& s : series_) {
        for (const Point& p : s.points) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
            if (p.x > 0) x0 = std::min(x0, std::log10(p.x)), x1 = std::max(x1, std::log10(p.x));
            if (p.y > 0) y0 = std::min(y0, std::log10(p.y)), y1 = std::max(y1, std::log10(p.y));
        }
    }
    if (x0 > x1) x0 = x1 = 0;  // nothing positive to place
    if (y0 > y1) y0 = y1 = 0;
    x0 = std::floor(x0) - 1, x1 = std::max(std::ceil(x1), x0 + 2);
    y0 = std::floor(y0) - 1, y1 = std::max(std::ceil(y1), y0 + 2);
    auto px = [&](double x) {
        const double e = x > 0 ? std::log10(x) : x0;
        return kLeft + (e - x0) / (x1 - x0) * (kW - kLeft - kRight);
    };
    auto py = [&](double y) {
        const double e = y > 0 ? std::log10(y) : y0;
        return kH - kBottom - (e - y0) / (y1 - y0) * (kH - kTop - kBottom);
    };

    std::ostringstream o;
    o << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kW << "' height='" << kH
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' "
         "fill='white'/>\n";
    o << "<text x='" << kW / 2 << "' y='20' text-anchor='middle' font-size='14'>" << title_
      << "</text>\n";
    for (double e = x0; e <= x1; ++e) {
        const double x = px(std::pow(10, e));
        o << "<line x1='" << num(x) << "' y1='" << kTop << "' x2='" << num(x) << "' y2='"
          << kH - kBottom << "' stroke='#ddd'/><text x='" << num(x) << "' y='" << kH - kBottom + 15
          << "' text-anchor='middle'>" << tick(std::pow(10, e)) << "</text>\n";
    }
    for (double e = y0; e <= y1; ++e) {
        const double y = py(std::pow(10, e));
        o << "<line x1='" << kLeft << "' y1='" << num(y) << "' x2='" << kW - kRight << "' y2='"
          << num(y) << "' stroke='#ddd'/><text x='" << kLeft - 5 << "' y='" << num(y + 4)
          << "' text-anchor='end'>" << (e == y0 ? "0" : tick(std::pow(10, e))) << "</text>\n";
    }
    o << "<text x='" << (kLeft + kW - kRight) / 2 << "' y='" << kH - 12 << "' text-anchor='middle'>"
      << x_label_ << "</text>\n<text transform='translate(16," << (kTop + kH - kBottom) / 2
      << ") rotate(-90)' text-anchor='middle'>" << y_label_ << "</text>\n";
    for (std::size_t s = 0; s < series_.size(); ++s) {
        const char* colour = kColours[s % std::size(kColours)];
        std::ostringstream path;
        for (const Point& p : series_[s].points) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
            path << (path.tellp() > 0 ? " L" : "M") << num(px(p.x)) << ',' << num(py(p.y));
        }
        o << "<path d='" << path.str() << "' fill='none' stroke='" << colour
          << "' stroke-width='1.5'/>\n";
        for (const Point& p : series_[s].points) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
            o << "<circle cx='" << num(px(p.x)) << "' cy='" << num(py(p.y)) << "' r='"
              << (p.highlighted ? 6 : 4) << "' fill='" << (p.failed ? "white" : colour)
              << "' stroke='" << (p.highlighted ? "black" : colour) << "' stroke-width='"
              << (p.highlighted ? 2 : 1) << "'/><text x='" << num(px(p.x) + 7) << "' y='"
              << num(py(p.y) - 6) << "' font-size='10'>" << p.label << "</text>\n";
        }
        const double ly = kTop + 20 * static_cast<double>(s);
        o << "<line x1='" << kW - kRight + 15 << "' y1='" << ly << "' x2='" << kW - kRight + 35
          << "' y2='" << ly << "' stroke='" << colour << "' stroke-width='2'/><text x='"
          << kW - kRight + 40 << "' y='" << ly + 4 << "'>" << series_[s].name << "</text>\n";
    }
    const double ly = kTop + 20 * static_cast<double>(series_.size()) + 10;
    o << "<circle cx='" << kW - kRight + 25 << "' cy='" << ly
      << "' r='6' fill='#888' stroke='black' stroke-width='2'/>"
      << "<text x='" << kW - kRight + 40 << "' y='" << ly + 4 << "'>Pareto front</text>\n"
      << "<circle cx='" << kW - kRight + 25 << "' cy='" << ly + 20
      << "' r='4' fill='white' stroke='#888'/>"
      << "<text x='" << kW - kRight + 40 << "' y='" << ly + 24 << "'>unstable</text>\n"
      << "<text x='" << kW - kRight + 15 << "' y='" << ly + 44
      << "' font-size='10'>labels: " << labels_ << "</text>\n</svg>\n";
    return o.str();
}
