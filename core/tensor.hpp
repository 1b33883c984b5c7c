// The matrix types of the network code: float32, column-major, one sample per column.
#pragma once

#include <Eigen/Core>

namespace rapid {

using Mat = Eigen::MatrixXf;
using Vec = Eigen::VectorXf;
using RowVec = Eigen::RowVectorXf;
using ConstMatRef = Eigen::Ref<const Mat>;
using VecRef = Eigen::Ref<Vec>;
using ConstVecRef = Eigen::Ref<const Vec>;

}  // namespace rapid
