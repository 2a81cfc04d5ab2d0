// The Pareto front of the error-against-time plot (report.h).
#include <cstddef>
#include <vector>

#include "bench/report.h"

namespace vkray::bench {

void markParetoFront(std::vector<ErrorPoint>& points) {
    // Quadratic, and fine: a bench has tens of configurations, not thousands.
    for (ErrorPoint& p : points) {
        p.pareto = true;
        for (const ErrorPoint& q : points) {
            const bool noWorse = q.totalMs() <= p.totalMs() && q.error.rmse <= p.error.rmse;
            const bool better = q.totalMs() < p.totalMs() || q.error.rmse < p.error.rmse;
            if (&q != &p && noWorse && better) {
                p.pareto = false;
                break;
            }
        }
    }
}

}  // namespace vkray::bench
