/* Plain textbook FASTSIM (Kalker 1982): the brush march with radial return onto the
 * Coulomb bound mu p, on the same discretisation as the project's steady FASTSIM:
 * ny strips (centres eta_j = -1 + (j + 1/2) 2/ny), nx cells per strip, nodes
 * xi_k = l_j - k dxi, the bound taken at the end node (no closer to the trailing edge
 * than half a cell), the spin lever arm at the move's midpoint, trapezoidal quadrature.
 * Reference for the benchmark only: gcc -O2, nothing clever. Returns F_x (N), writes F_y. */
#include <math.h>

double fastsim_ref(int nx, int ny, double a, double b, double p0, double mu,
                   double lx, double ly, double ls, double cx, double cy, double cs,
                   double *fy_out)
{
    double fx = 0.0, fy = 0.0;
    double dy = 2.0 * b / ny;
    for (int j = 0; j < ny; j++) {
        double eta = -1.0 + (j + 0.5) * 2.0 / ny;
        double l = sqrt(1.0 - eta * eta);
        double dxi = 2.0 * l / nx;
        double d = dxi * a;
        double y = eta * b;
        double tx = 0.0, ty = 0.0;
        double sx = 0.5 * tx, sy = 0.5 * ty; /* node 0: zero stress, half weight */
        for (int k = 1; k <= nx; k++) {
            double xi = l - k * dxi;
            double x = a * (xi + 0.5 * dxi);
            tx += d * (cx / lx - cs * y / ls);
            ty += d * (cy / ly + cs * x / ls);
            double xe = xi > -l + 0.5 * dxi ? xi : -l + 0.5 * dxi;
            double r = 1.0 - xe * xe - eta * eta;
            double g = r > 0.0 ? mu * p0 * sqrt(r) : 0.0;
            double n = sqrt(tx * tx + ty * ty);
            if (g <= 0.0) {
                tx = 0.0;
                ty = 0.0;
            } else if (n > g) {
                tx *= g / n;
                ty *= g / n;
            }
            double w = k < nx ? 1.0 : 0.5;
            sx += w * tx;
            sy += w * ty;
        }
        fx += sx * dxi * a * dy;
        fy += sy * dxi * a * dy;
    }
    *fy_out = fy;
    return fx;
}
