// The symbolic analysis of the multifrontal factorization (multifrontal_factorization.h): the
// elimination tree (Liu 1986), its postorder, the factor's column counts (Gilbert, Ng & Peyton
// 1994), fundamental supernodes merged by relaxed amalgamation (Ashcraft & Grimes 1989), and
// each front's rows. Done once per pattern and order; every numeric factorization reuses it.
#include "solver/multifrontal_factorization.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace raps {
namespace {

// Relaxed amalgamation (Ashcraft & Grimes; the thresholds CHOLMOD uses): merging a supernode
// into its parent stores some explicit zeros but turns many tiny dense kernels into fewer larger
// ones, which is faster as long as the zeros stay a small fraction.
bool worth_merging(int64_t columns, double zero_fraction) {
    return columns <= 4 || (columns <= 16 && zero_fraction < 0.8) ||
           (columns <= 48 && zero_fraction < 0.1) || zero_fraction < 0.05;
}

// Elimination tree of the pattern eliminated in `order` (Liu's algorithm with path compression):
// parent[k] of the k-th eliminated unknown, in elimination positions, or -1 for a root.
std::vector<int32_t> elimination_tree(const SparsePattern& pattern,
                                      const std::vector<int32_t>& order,
                                      const std::vector<int32_t>& position,
                                      const ProgressSpan& progress) {
    const int32_t n = pattern.size;
    std::vector<int32_t> parent(n, -1), ancestor(n, -1);
    for (int32_t i = 0; i < n; ++i) {
        progress.at(i, n);
        const int32_t row = order[i];
        for (int32_t p = pattern.row_offsets[row]; p < pattern.row_offsets[row + 1]; ++p) {
            int32_t j = position[pattern.columns[p]];
            while (j < i) {
                const int32_t next = ancestor[j];
                ancestor[j] = i;
                if (next < 0) {
                    parent[j] = i;
                    break;
                }
                j = next;
            }
        }
    }
    return parent;
}

// The tree's postorder (postorder[k]: the node visited k-th, children before parents, each
// subtree a contiguous range ending at its root), a pass over the tree per report.
std::vector<int32_t> tree_postorder(const std::vector<int32_t>& parent,
                                    const ProgressSpan& progress) {
    const int32_t n = static_cast<int32_t>(parent.size());
    std::vector<int32_t> first_child(n, -1), next_sibling(n, -1);
    for (int32_t j = n - 1; j >= 0; --j) {
        if (parent[j] >= 0) {
            next_sibling[j] = first_child[parent[j]];
            first_child[parent[j]] = j;
        }
    }
    progress.report(0.3);
    std::vector<int32_t> postorder;
    postorder.reserve(n);
    std::vector<int32_t> stack;
    for (int32_t root = 0; root < n; ++root) {
        if (parent[root] >= 0) continue;
        stack.push_back(root);
        while (!stack.empty()) {
            const int32_t j = stack.back();
            if (first_child[j] >= 0) {
                const int32_t c = first_child[j];
                first_child[j] = next_sibling[c];
                stack.push_back(c);
            } else {
                stack.pop_back();
                progress.at(static_cast<int64_t>(postorder.size()), n, 0.3, 1.0);
                postorder.push_back(j);
            }
        }
    }
    return postorder;
}

// Column counts of L (diagonal included) without forming L (Gilbert, Ng & Peyton 1994, as in
// CSparse's cs_counts): row i of L is the row subtree spanned by the columns of A's row i; each
// column j counts the row subtrees it lies in, found from the subtrees' leaves and their least
// common ancestors. Walking every row subtree instead, O(|L|), was a quarter of the analysis.
// Columns are numbered in postorder (order: position -> unknown), so j's subtree is
// first[j] .. j.
std::vector<int64_t> column_counts(const SparsePattern& pattern, const std::vector<int32_t>& order,
                                   const std::vector<int32_t>& position,
                                   const std::vector<int32_t>& parent,
                                   const ProgressSpan& progress) {
    const int32_t n = pattern.size;
    std::vector<int64_t> column_count(n, 0);
    std::vector<int32_t> first(n, -1), max_first(n, -1), previous_leaf(n, -1), ancestor(n);
    std::iota(ancestor.begin(), ancestor.end(), 0);  // union-find of finished subtrees
    for (int32_t j = 0; j < n; ++j) {
        if (first[j] < 0) {
            column_count[j] = 1;  // a leaf of the tree
            for (int32_t k = j; k >= 0 && first[k] < 0; k = parent[k]) first[k] = j;
        }
    }
    progress.report(0.1);
    for (int32_t j = 0; j < n; ++j) {
        progress.at(j, n, 0.1, 0.9);
        if (parent[j] >= 0) --column_count[parent[j]];
        const int32_t row = order[j];
        for (int32_t p = pattern.row_offsets[row]; p < pattern.row_offsets[row + 1]; ++p) {
            const int32_t i = position[pattern.columns[p]];
            if (i <= j || first[j] <= max_first[i]) continue;  // j is no leaf of i's subtree
            max_first[i] = first[j];
            const int32_t previous = previous_leaf[i];
            previous_leaf[i] = j;
            ++column_count[j];
            if (previous < 0) continue;  // i's first leaf
            int32_t common = previous;   // least common ancestor of the two leaves
            while (common != ancestor[common]) common = ancestor[common];
            for (int32_t k = previous; k != common;) {  // path compression
                const int32_t up = ancestor[k];
                ancestor[k] = common;
                k = up;
            }
            --column_count[common];
        }
        if (parent[j] >= 0) ancestor[j] = parent[j];
    }
    progress.report(0.9);
    for (int32_t j = 0; j < n; ++j) {
        if (parent[j] >= 0) column_count[parent[j]] += column_count[j];
    }
    return column_count;
}

// Fundamental supernodes: chains j -> j + 1 where j is the only child and the structure shrinks
// by exactly the diagonal. The first column of each, then n.
std::vector<int32_t> fundamental_supernodes(const std::vector<int32_t>& parent,
                                            const std::vector<int64_t>& column_count) {
    const int32_t n = static_cast<int32_t>(parent.size());
    std::vector<int32_t> child_count(n, 0);
    for (int32_t j = 0; j < n; ++j) {
        if (parent[j] >= 0) ++child_count[parent[j]];
    }
    std::vector<int32_t> super_first;
    super_first.reserve(static_cast<size_t>(n) + 1);  // no doubling copies (tens of MB)
    for (int32_t j = 0; j < n; ++j) {
        const bool continues = j > 0 && parent[j - 1] == j && child_count[j] == 1 &&
                               column_count[j - 1] == column_count[j] + 1;
        if (!continues) super_first.push_back(j);
    }
    super_first.push_back(n);
    return super_first;
}

// Relaxed amalgamation, from the last supernode down: supernode s merges into the group that
// starts right after it when that group holds its parent column. merged_with_next[s] for each
// fundamental supernode.
std::vector<char> relaxed_amalgamation(const std::vector<int32_t>& super_first,
                                       const std::vector<int32_t>& parent,
                                       const std::vector<int64_t>& column_count) {
    const int32_t fundamental_count = static_cast<int32_t>(super_first.size()) - 1;
    std::vector<char> merged_with_next(fundamental_count, 0);
    {
        // Stats of the group starting at supernode s+1 (the one s may join).
        int64_t group_columns = 0, group_rows = 0;
        double group_nonzeros = 0;
        for (int32_t s = fundamental_count - 1; s >= 0; --s) {
            const int32_t f = super_first[s], l = super_first[s + 1] - 1;
            const int64_t cols = l - f + 1;
            double nonzeros = 0;
            for (int32_t j = f; j <= l; ++j) nonzeros += static_cast<double>(column_count[j]);
            const int64_t rows = column_count[f];
            bool merge = false;
            if (s + 1 < fundamental_count && parent[l] == super_first[s + 1]) {
                const int64_t merged_columns = cols + group_columns;
                const int64_t merged_rows = cols + group_rows;
                const double entries = static_cast<double>(merged_columns) * merged_rows -
                                       0.5 * static_cast<double>(merged_columns) *
                                           static_cast<double>(merged_columns - 1);
                const double zero_fraction = 1.0 - (nonzeros + group_nonzeros) / entries;
                merge = worth_merging(merged_columns, zero_fraction);
                if (merge) {
                    group_columns = merged_columns;
                    group_rows = merged_rows;
                    group_nonzeros += nonzeros;
                }
            }
            merged_with_next[s] = merge;
            if (!merge) {
                group_columns = cols;
                group_rows = rows;
                group_nonzeros = nonzeros;
            }
        }
    }
    return merged_with_next;
}

}  // namespace

void MultifrontalFactorization::analyze(const SparsePattern& pattern,
                                        const std::vector<int32_t>& order,
                                        const ProgressSpan& progress) {
    const int32_t n = pattern.size;
    size_ = n;
    prepared_ = false;
    std::vector<int32_t> position(n);
    for (int32_t k = 0; k < n; ++k) position[order[k]] = k;
    std::vector<int32_t> parent =
        elimination_tree(pattern, order, position, progress.part(0.0, 0.15));

    // Postorder the tree so that every subtree is a contiguous range ending at its root; the
    // fill is unchanged and supernodes become ranges of consecutive columns.
    const ProgressSpan renumbering = progress.part(0.15, 0.2);
    const std::vector<int32_t> postorder = tree_postorder(parent, renumbering.part(0.0, 0.6));
    order_.resize(n);
    std::vector<int32_t> renumber(n);
    for (int32_t k = 0; k < n; ++k) {
        order_[k] = order[postorder[k]];
        renumber[postorder[k]] = k;
    }
    renumbering.report(0.7);
    for (int32_t k = 0; k < n; ++k) position[order_[k]] = k;
    renumbering.report(0.8);
    {
        std::vector<int32_t> renumbered_parent(n, -1);
        for (int32_t j = 0; j < n; ++j) {
            if (parent[j] >= 0) renumbered_parent[renumber[j]] = renumber[parent[j]];
        }
        parent.swap(renumbered_parent);
    }
    renumbering.report(1.0);

    const std::vector<int64_t> column_count =
        column_counts(pattern, order_, position, parent, progress.part(0.2, 0.4));
    const ProgressSpan grouping = progress.part(0.4, 0.45);
    const std::vector<int32_t> super_first = fundamental_supernodes(parent, column_count);
    grouping.report(0.3);
    const std::vector<char> merged_with_next =
        relaxed_amalgamation(super_first, parent, column_count);
    grouping.report(0.6);
    build_supernodes(super_first, merged_with_next, parent, grouping.part(0.6, 1.0));
    build_front_rows(pattern, position, progress.part(0.45, 0.8));
    build_relative_rows(progress.part(0.8, 1.0));
}

void MultifrontalFactorization::build_supernodes(const std::vector<int32_t>& super_first,
                                                 const std::vector<char>& merged_with_next,
                                                 const std::vector<int32_t>& parent,
                                                 const ProgressSpan& progress) {
    // Progress: a report after each pass (over the columns or the supernodes).
    const int32_t n = size_;
    const int32_t fundamental_count = static_cast<int32_t>(super_first.size()) - 1;
    std::vector<int32_t> supernode_of(n);
    supernodes_.clear();
    supernodes_.reserve(fundamental_count);
    for (int32_t s = 0; s < fundamental_count; ++s) {
        if (s == 0 || !merged_with_next[s - 1]) {
            Supernode node{};
            node.first_column = super_first[s];
            supernodes_.push_back(node);
        }
        supernodes_.back().columns = super_first[s + 1] - supernodes_.back().first_column;
    }
    progress.report(0.2);
    const int32_t supernode_count = static_cast<int32_t>(supernodes_.size());
    for (int32_t s = 0; s < supernode_count; ++s) {
        const Supernode& node = supernodes_[s];
        for (int32_t j = node.first_column; j < node.first_column + node.columns; ++j) {
            supernode_of[j] = s;
        }
    }
    progress.report(0.4);
    std::vector<int32_t> super_parent(supernode_count, -1);
    for (int32_t s = 0; s < supernode_count; ++s) {
        const int32_t last = supernodes_[s].first_column + supernodes_[s].columns - 1;
        if (parent[last] >= 0) super_parent[s] = supernode_of[parent[last]];
    }
    progress.report(0.6);
    // Children lists (postorder keeps them in increasing order, which the stack relies on).
    std::vector<int32_t> children_count(supernode_count, 0);
    for (int32_t s = 0; s < supernode_count; ++s) {
        if (super_parent[s] >= 0) ++children_count[super_parent[s]];
    }
    progress.report(0.8);
    {
        int32_t offset = 0;
        for (int32_t s = 0; s < supernode_count; ++s) {
            supernodes_[s].child_begin = supernodes_[s].child_end = offset;
            offset += children_count[s];
        }
        child_list_.assign(offset, 0);
        for (int32_t s = 0; s < supernode_count; ++s) {
            if (super_parent[s] >= 0) {
                Supernode& p = supernodes_[super_parent[s]];
                child_list_[p.child_end++] = s;
            }
        }
    }
    progress.report(1.0);
}

void MultifrontalFactorization::build_front_rows(const SparsePattern& pattern,
                                                 const std::vector<int32_t>& position,
                                                 const ProgressSpan& progress) {
    const int32_t n = size_;
    const int32_t supernode_count = static_cast<int32_t>(supernodes_.size());
    // Front structures: the supernode's columns, then the rows below it from A's columns and
    // from its children's update rows, sorted.
    row_indices_.clear();
    std::vector<int32_t> mark(n, -1);
    const ProgressSpan& fronts = progress;
    for (int32_t s = 0; s < supernode_count; ++s) {
        fronts.at(s, supernode_count);
        Supernode& node = supernodes_[s];
        const int32_t f = node.first_column, l = f + node.columns - 1;
        node.row_offset = static_cast<int64_t>(row_indices_.size());
        for (int32_t j = f; j <= l; ++j) row_indices_.push_back(j);
        const size_t update_begin = row_indices_.size();
        for (int32_t j = f; j <= l; ++j) {
            const int32_t column = order_[j];
            for (int32_t p = pattern.row_offsets[column]; p < pattern.row_offsets[column + 1];
                 ++p) {
                const int32_t i = position[pattern.columns[p]];
                if (i > l && mark[i] != s) {
                    mark[i] = s;
                    row_indices_.push_back(i);
                }
            }
        }
        for (int32_t c = node.child_begin; c < node.child_end; ++c) {
            const Supernode& child = supernodes_[child_list_[c]];
            for (int64_t r = child.row_offset + child.columns; r < child.row_offset + child.rows;
                 ++r) {
                const int32_t i = row_indices_[r];
                if (i > l && mark[i] != s) {
                    mark[i] = s;
                    row_indices_.push_back(i);
                }
            }
        }
        std::sort(row_indices_.begin() + static_cast<int64_t>(update_begin), row_indices_.end());
        node.rows = static_cast<int32_t>(row_indices_.size() - node.row_offset);
    }
}

void MultifrontalFactorization::build_relative_rows(const ProgressSpan& progress) {
    const int32_t n = size_;
    const int32_t supernode_count = static_cast<int32_t>(supernodes_.size());
    // Where each child's update rows land in its parent's front.
    std::vector<int32_t> local(n, -1);
    relative_rows_.clear();
    int64_t max_front = 0;
    for (const Supernode& node : supernodes_) {
        max_front = std::max(max_front, static_cast<int64_t>(node.rows) * node.rows);
    }
    const ProgressSpan& relative = progress;
    for (int32_t s = 0; s < supernode_count; ++s) {
        relative.at(s, supernode_count);
        const Supernode& node = supernodes_[s];
        for (int32_t r = 0; r < node.rows; ++r) local[row_indices_[node.row_offset + r]] = r;
        for (int32_t c = node.child_begin; c < node.child_end; ++c) {
            Supernode& child = supernodes_[child_list_[c]];
            child.relative_offset = static_cast<int64_t>(relative_rows_.size());
            for (int64_t r = child.row_offset + child.columns; r < child.row_offset + child.rows;
                 ++r) {
                relative_rows_.push_back(local[row_indices_[r]]);
            }
        }
    }
    // Peak of the contribution-block stack, simulated in the factorization's order.
    {
        int64_t stack = 0;
        stack_peak_ = 0;
        std::vector<int64_t> stack_sizes;
        for (int32_t s = 0; s < supernode_count; ++s) {
            const Supernode& node = supernodes_[s];
            for (int32_t c = node.child_begin; c < node.child_end; ++c) {
                stack -= stack_sizes.back();
                stack_sizes.pop_back();
            }
            const int64_t update = node.rows - node.columns;
            stack_sizes.push_back(update * update);
            stack += update * update;
            stack_peak_ = std::max(stack_peak_, stack);
        }
    }
    front_ = allocate(max_front);
    front_capacity_ = max_front;
    stack_ = allocate(stack_peak_);
}

}  // namespace raps
