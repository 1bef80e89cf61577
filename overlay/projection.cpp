#include "projection.h"

#include <cmath>

namespace physhand::overlay {

Mat4 view_projection(const Eye& eye) {
    // Rotation of the eye (unit quaternion) as a 3x3 matrix R, rows r[i]; the view
    // transform is R^T (p - eye.position).
    const double x = eye.orientation.x, y = eye.orientation.y, z = eye.orientation.z,
                 w = eye.orientation.w;
    const double r[3][3] = {
        {1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
        {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
        {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)},
    };
    const double eye_position[3] = {eye.position.x, eye.position.y, eye.position.z};
    double view[3][4];  // rows of the 3x4 view matrix
    for (int i = 0; i < 3; ++i) {
        view[i][3] = 0.0;
        for (int j = 0; j < 3; ++j) {
            view[i][j] = r[j][i];
            view[i][3] -= r[j][i] * eye_position[j];
        }
    }

    // Asymmetric frustum from the four half-angles (OpenXR: left and down negative).
    const double left = std::tan(eye.angle_left), right = std::tan(eye.angle_right);
    const double up = std::tan(eye.angle_up), down = std::tan(eye.angle_down);
    // Rows of the projection applied to view space (x right, y up, -z forward):
    // clip = (P0 . v, P1 . v, near, -z).
    const double p0[3] = {2 / (right - left), 0, (right + left) / (right - left)};
    const double p1[3] = {0, -2 / (up - down), -(up + down) / (up - down)};

    Mat4 m{};
    const auto set = [&m](int row, int column, double value) {
        m[column * 4 + row] = static_cast<float>(value);
    };
    for (int column = 0; column < 4; ++column) {
        double row0 = 0, row1 = 0;
        for (int k = 0; k < 3; ++k) {
            row0 += p0[k] * view[k][column];
            row1 += p1[k] * view[k][column];
        }
        set(0, column, row0);
        set(1, column, row1);
        set(3, column, -view[2][column]);
    }
    set(2, 3, kNearZ);
    return m;
}

}  // namespace physhand::overlay
