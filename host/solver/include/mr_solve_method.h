/* mr_solve_method: which linear solver the constraint system uses (§4.3).
 *
 * The one list of solver methods and their names, for every library and
 * program that names one (the physics' world definition, the scene reader,
 * the command line). Nothing else of the solver comes with it.
 */
#ifndef MR_SOLVE_METHOD_H
#define MR_SOLVE_METHOD_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mr_solve_method {
  MR_SOLVE_GAUSS_SEIDEL, /* "gauss-seidel": the paper's iteration (§4.3) */
  MR_SOLVE_CG,           /* "cg": Jacobi-preconditioned conjugate gradient */
  MR_SOLVE_LDLT,         /* "ldlt": sparse LDLᵀ, exact to rounding; the default */
  MR_SOLVE_EIGEN,        /* "eigen": Eigen's SimplicialLDLT, the tests' oracle */
  MR_SOLVE_METHOD_COUNT
} mr_solve_method;

/* The method's name, or "unknown" for a value outside the enum. */
const char *mr_solve_method_name(mr_solve_method m);
/* 0 and *out set, or -1 (and *out untouched) for a name not in the list. */
int mr_solve_method_parse(const char *name, mr_solve_method *out);
/* Every name in enum order, then NULL: for "expected one of" messages. */
const char *const *mr_solve_method_names(void);

#ifdef __cplusplus
}
#endif

#endif /* MR_SOLVE_METHOD_H */
