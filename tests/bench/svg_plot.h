#pragma once

#include <string>
#include <vector>

// A small log-log scatter plot with one line per series, written as SVG. Zero values sit on
// the axis' lowest line, marked 0.
class SvgPlot {
  public:
    struct Point {
        double x, y;
        std::string label;
        bool highlighted;  // e.g. on the Pareto front
        bool failed;       // drawn hollow
    };
    // `labels` says what the points' labels are (legend).
    SvgPlot(std::string title, std::string x_label, std::string y_label, std::string labels);
    void add_series(const std::string& name, const std::vector<Point>& points);
    std::string render() const;

  private:
    struct Series {
        std::string name;
        std::vector<Point> points;
    };
    std::string title_, x_label_, y_label_, labels_;
    std::vector<Series> series_;
};
