// CMA-ES, (mu/mu_w, lambda) with rank-one and rank-mu updates and
// cumulative step-size adaptation (Hansen, "The CMA Evolution Strategy: A
// Tutorial", 2016), in ask/tell form. Written against Eigen rather than
// taken from pagmo 2.18 (docs/optimizer.md says why).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "optimizer/search/algorithm.h"
#include "optimizer/search/random.h"

namespace mrsim {

class Cmaes : public Algorithm {
 public:
  Cmaes(const GenomeSpec& spec, const AlgorithmSettings& settings);
  std::vector<Genome> Ask() override;
  void Tell(const std::vector<EvalResult>& results) override;

  // Step size (fraction of each gene's range) after the last update.
  double sigma() const { return sigma_; }

 private:
  // The search runs in [0, 1] per enabled gene (of non-zero range), so one
  // step size fits genes of any unit.
  Genome ToGenome(const Eigen::VectorXd& u) const;
  Eigen::VectorXd ToUnit(const Genome& g) const;
  void Update();

  GenomeSpec spec_;
  AlgorithmSettings settings_;
  Random random_;
  std::vector<int> dims_;  // gene index of each search dimension
  int lambda_ = 0;
  int mu_ = 0;
  Eigen::VectorXd weights_;
  double mueff_ = 0, cc_ = 0, cs_ = 0, c1_ = 0, cmu_ = 0, damps_ = 0;
  double chi_n_ = 0;

  Eigen::VectorXd mean_;
  double sigma_ = 0;
  Eigen::MatrixXd c_, b_;
  Eigen::VectorXd d_;  // square roots of C's eigenvalues
  Eigen::VectorXd pc_, ps_;
  int updates_ = 0;

  std::vector<Genome> population_;
  std::vector<Eigen::VectorXd> unit_;  // population_ in search coordinates
  std::vector<double> fitness_;
  bool told_ = false;
};

}  // namespace mrsim
