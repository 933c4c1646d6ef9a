#include "optimizer/search/cmaes.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "optimizer/search/operators.h"

namespace mrsim {

Cmaes::Cmaes(const GenomeSpec& spec, const AlgorithmSettings& settings)
    : spec_(spec), settings_(settings), random_(settings.seed) {
  for (int i = 0; i < spec_.size(); ++i) {
    const GeneSpec& g = spec_.genes[i];
    if (g.enabled && g.upper > g.lower) dims_.push_back(i);
  }
  const int n = static_cast<int>(dims_.size());
  lambda_ = settings_.population;
  mu_ = std::max(1, lambda_ / 2);
  weights_.resize(mu_);
  for (int i = 0; i < mu_; ++i) {
    weights_[i] = std::log(mu_ + 0.5) - std::log(i + 1.0);
  }
  weights_ /= weights_.sum();
  mueff_ = 1.0 / weights_.squaredNorm();
  const double nd = std::max(n, 1);
  cc_ = (4 + mueff_ / nd) / (nd + 4 + 2 * mueff_ / nd);
  cs_ = (mueff_ + 2) / (nd + mueff_ + 5);
  c1_ = 2 / ((nd + 1.3) * (nd + 1.3) + mueff_);
  cmu_ = std::min(
      1 - c1_, 2 * (mueff_ - 2 + 1 / mueff_) / ((nd + 2) * (nd + 2) + mueff_));
  damps_ = 1 + 2 * std::max(0.0, std::sqrt((mueff_ - 1) / (nd + 1)) - 1) + cs_;
  chi_n_ = std::sqrt(nd) * (1 - 1 / (4 * nd) + 1 / (21 * nd * nd));

  sigma_ = settings_.cmaes_sigma;
  c_ = Eigen::MatrixXd::Identity(n, n);
  b_ = Eigen::MatrixXd::Identity(n, n);
  d_ = Eigen::VectorXd::Ones(n);
  pc_ = Eigen::VectorXd::Zero(n);
  ps_ = Eigen::VectorXd::Zero(n);
}

Genome Cmaes::ToGenome(const Eigen::VectorXd& u) const {
  Genome g = spec_.StartGenome();
  for (size_t k = 0; k < dims_.size(); ++k) {
    const GeneSpec& s = spec_.genes[dims_[k]];
    g[dims_[k]] = spec_.Legal(dims_[k], s.lower + u[k] * (s.upper - s.lower));
  }
  return g;
}

Eigen::VectorXd Cmaes::ToUnit(const Genome& g) const {
  Eigen::VectorXd u(dims_.size());
  for (size_t k = 0; k < dims_.size(); ++k) {
    const GeneSpec& s = spec_.genes[dims_[k]];
    u[k] = (g[dims_[k]] - s.lower) / (s.upper - s.lower);
  }
  return u;
}

std::vector<Genome> Cmaes::Ask() {
  if (!population_.empty() && !told_) return population_;  // asked twice
  if (population_.empty()) {
    // Without a start genome, the centre of the limits: sigma 0.3 then
    // covers the whole box.
    mean_ = settings_.include_start ? ToUnit(spec_.StartGenome())
                                    : Eigen::VectorXd::Constant(
                                          static_cast<int>(dims_.size()), 0.5);
  } else {
    Update();
  }
  population_.clear();
  unit_.clear();
  const int n = static_cast<int>(dims_.size());
  for (int i = 0; i < lambda_; ++i) {
    Eigen::VectorXd z(n);
    for (int k = 0; k < n; ++k) z[k] = random_.Normal();
    // Generation 0 holds the start genome itself as individual 0.
    if (updates_ == 0 && i == 0 && settings_.include_start) z.setZero();
    const Eigen::VectorXd x = mean_ + sigma_ * (b_ * d_.asDiagonal() * z);
    // The limits repair the point; the update learns from the repaired
    // point, the one that was evaluated.
    population_.push_back(ToGenome(x));
    unit_.push_back(ToUnit(population_.back()));
  }
  told_ = false;
  return population_;
}

void Cmaes::Tell(const std::vector<EvalResult>& results) {
  if (results.size() != population_.size()) {
    throw std::invalid_argument("CMA-ES: results do not match the generation");
  }
  fitness_.clear();
  for (const EvalResult& r : results) fitness_.push_back(r.fitness);
  told_ = true;
}

void Cmaes::Update() {
  const int n = static_cast<int>(dims_.size());
  if (n == 0) return;
  const std::vector<int> ranking = RankByFitness(fitness_);  // best first
  const Eigen::VectorXd old_mean = mean_;
  Eigen::MatrixXd steps(n, mu_);  // (x_i:lambda - old mean) / sigma
  mean_.setZero();
  for (int i = 0; i < mu_; ++i) {
    mean_ += weights_[i] * unit_[ranking[i]];
    steps.col(i) = (unit_[ranking[i]] - old_mean) / sigma_;
  }
  const Eigen::VectorXd mean_step = (mean_ - old_mean) / sigma_;
  // C^-1/2 = B D^-1 B^T.
  const Eigen::MatrixXd inv_sqrt_c =
      b_ * d_.cwiseInverse().asDiagonal() * b_.transpose();
  ps_ = (1 - cs_) * ps_ +
        std::sqrt(cs_ * (2 - cs_) * mueff_) * (inv_sqrt_c * mean_step);
  ++updates_;
  const double ps_norm = ps_.norm();
  const bool hsig =
      ps_norm / std::sqrt(1 - std::pow(1 - cs_, 2.0 * updates_)) / chi_n_ <
      1.4 + 2.0 / (n + 1);
  pc_ = (1 - cc_) * pc_ +
        (hsig ? std::sqrt(cc_ * (2 - cc_) * mueff_) : 0.0) * mean_step;
  c_ = (1 - c1_ - cmu_) * c_ +
       c1_ * (pc_ * pc_.transpose() + (hsig ? 0.0 : cc_ * (2 - cc_)) * c_) +
       cmu_ * steps * weights_.asDiagonal() * steps.transpose();
  sigma_ *= std::exp((cs_ / damps_) * (ps_norm / chi_n_ - 1));
  // Past the whole box the step size means nothing; below 1e-12 the
  // population has converged to one point.
  sigma_ = std::clamp(sigma_, 1e-12, 1.0);

  c_ = 0.5 * (c_ + c_.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(c_);
  if (eigen.info() != Eigen::Success) {
    // Numerically broken C: start the shape again, keep mean and step.
    c_.setIdentity();
    b_.setIdentity();
    d_.setOnes();
    return;
  }
  b_ = eigen.eigenvectors();
  d_ = eigen.eigenvalues().cwiseMax(1e-20).cwiseSqrt();
}

}  // namespace mrsim
