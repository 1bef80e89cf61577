#pragma once

#include <string>
#include <vector>

// A small log-log scatter plot with one line per series, written as SVG.
class SvgPlot {
  public:
    struct Point {
        double x, y;
        std::string label;
        bool highlighted;  // e.g. on the Pareto front
        bool failed;       // drawn hollow
    };
    SvgPlot(std::string title, std::string x_label, std::string y_label);
    void add_series(const std::string& name, const std::vector<Point>& points);
    std::string render() const;

  private:
    struct Series {
        std::string name;
        std::vector<Point> points;
    };
    std::string title_, x_label_, y_label_;
    std::vector<Series> series_;
};
