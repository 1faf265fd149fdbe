#pragma once
// The vector and matrix types shared by models and integrators (Eigen, dynamic size).
#include <Eigen/Dense>

namespace contact {
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;
using ConstVectorRef = Eigen::Ref<const Vector>;
using VectorRef = Eigen::Ref<Vector>;
using MatrixRef = Eigen::Ref<Matrix>;
}  // namespace contact
