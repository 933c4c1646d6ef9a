// Genetic operators on genomes. Every genome they return is legal for the
// spec: within limits, integer genes whole, disabled genes at their start.
#pragma once

#include <vector>

#include "optimizer/search/genome.h"
#include "optimizer/search/random.h"

namespace mrsim {

// Each gene from parent a or b with probability 1/2.
Genome UniformCrossover(const GenomeSpec& spec, const Genome& a,
                        const Genome& b, Random& random);

// Each enabled gene, with probability `rate`, moves by a normal step of
// standard deviation scale * (upper - lower) and is clamped to its limits
// (an integer gene moves by at least one when it moves).
void Mutate(const GenomeSpec& spec, Genome& genome, double rate, double scale,
            Random& random);

// Indices sorted from best to worst fitness; ties keep index order.
std::vector<int> RankByFitness(const std::vector<double>& fitness);

// The best of k uniformly drawn individuals (ties: the lower index).
int TournamentSelect(const std::vector<double>& fitness, int k, Random& random);

// A uniform pick among the best `fraction` of the population (at least one).
int TruncationSelect(const std::vector<int>& ranking, double fraction,
                     Random& random);

}  // namespace mrsim
