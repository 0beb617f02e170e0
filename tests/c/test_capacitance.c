static char help[] = "Verification of BoltCapacitance (src/sys/capacitance.c), the small system of the FOM's and the\n"
                     "ROM's low-rank updates, against a direct solve of the changed matrix.\n"
                     "A random symmetric positive definite A_ref (n = 60) changed by U S U' with 12 node pairs\n"
                     "(36 columns of U, stored in a shuffled pool of G): S block-diagonal with symmetric blocks of\n"
                     "rank 0 to 3, definite and indefinite (the symmetric path), and the same S with a coupling\n"
                     "between two pairs (the general path). x = y - Z w with w from the capacitance must equal\n"
                     "(A_ref + U S U')^-1 b from LAPACK's LU; entries of the pool's G outside the correction are\n"
                     "set to 1e300, so that reading one shows. Prints PASS/FAIL name value per check; exits\n"
                     "non-zero if any check fails.\n";

#include <boltrom.h>
#include <petscblaslapack.h>

#define N  60
#define K  12
#define M  (3 * K)
#define LD 48 /* the pool's columns: more than the correction's, in another order */

static unsigned long state = 88172645463325252UL;
static PetscReal     Rand(void) /* xorshift, uniform in (-1, 1) */
{
  state ^= state << 13;
  state ^= state >> 7;
  state ^= state << 17;
  return 2.0 * (PetscReal)(state % 1000003) / 1000003.0 - 1.0;
}

static PetscErrorCode Report(const char *name, PetscReal value, PetscBool ok, PetscInt *nfail)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s %s %.6e\n", ok ? "PASS" : "FAIL", name, (double)value));
  if (!ok) (*nfail)++;
  PetscFunctionReturn(0);
}

/* x = A^-1 B (n x nrhs) by LU, A kept */
static PetscErrorCode DenseSolve(PetscInt n, const PetscReal A[], PetscInt nrhs, PetscReal B[], PetscBool *singular)
{
  PetscReal   *F;
  PetscBLASInt bn, br, *piv, info;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(n * n, &F, n, &piv));
  PetscCall(PetscArraycpy(F, A, n * n));
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCall(PetscBLASIntCast(nrhs, &br));
  PetscCallBLAS("LAPACKgesv", LAPACKgesv_(&bn, &br, F, &bn, piv, B, &bn, &info));
  *singular = (PetscBool)(info != 0);
  PetscCall(PetscFree2(F, piv));
  PetscFunctionReturn(0);
}

/* The Woodbury solve through the capacitance against LAPACK on A_ref + U S U'. */
static PetscErrorCode Compare(const char *name, const PetscReal A[], const PetscReal U[], const PetscReal S[], const PetscReal Zpool[], const PetscReal Gpool[], const PetscInt idx[], const PetscReal b[], PetscInt *nfail)
{
  BoltCapacitance *cap;
  PetscReal        Af[N * N], x[N], y[N], t[M], w[M], err = 0, ref = 0;
  PetscBool        ok, singular;

  PetscFunctionBeginUser;
  /* the reference: A_ref + U S U', solved directly */
  for (PetscInt i = 0; i < N; i++)
    for (PetscInt j = 0; j < N; j++) {
      PetscReal v = A[i + N * j];
      for (PetscInt p = 0; p < M; p++)
        for (PetscInt q = 0; q < M; q++) v += U[i + N * p] * S[p + M * q] * U[j + N * q];
      Af[i + N * j] = v;
    }
  PetscCall(PetscArraycpy(x, b, N));
  PetscCall(DenseSolve(N, Af, 1, x, &singular));
  /* the correction: y = A_ref^-1 b, t = U' y, x_c = y - Z w */
  PetscCall(PetscArraycpy(y, b, N));
  PetscCall(DenseSolve(N, A, 1, y, &singular));
  for (PetscInt p = 0; p < M; p++) {
    t[p] = 0;
    for (PetscInt i = 0; i < N; i++) t[p] += U[i + N * p] * y[i];
  }
  PetscCall(BoltCapacitanceCreate(&cap));
  PetscCall(BoltCapacitanceFactor(cap, M, S, Gpool, LD, idx, &ok));
  PetscCall(Report(name, 0, ok, nfail));
  PetscCall(BoltCapacitanceSolve(cap, t, w));
  for (PetscInt i = 0; i < N; i++) {
    PetscReal v = y[i];
    for (PetscInt p = 0; p < M; p++) v -= Zpool[i + N * idx[p]] * w[p];
    err = PetscMax(err, PetscAbsReal(v - x[i]));
    ref = PetscMax(ref, PetscAbsReal(x[i]));
  }
  PetscCall(BoltCapacitanceDestroy(&cap));
  {
    char what[128];
    PetscCall(PetscSNPrintf(what, sizeof(what), "%s_solve_error", name));
    PetscCall(Report(what, err / ref, (PetscBool)(err / ref < 1e-10), nfail));
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscReal A[N * N], U[N * M], S[M * M], Zpool[N * LD], Gpool[LD * LD], b[N];
  PetscInt  idx[M], slot[LD], nfail = 0;
  PetscBool singular;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  /* A_ref = R R' + N I, well conditioned, symmetric positive definite */
  {
    PetscReal R[N * N];
    for (PetscInt i = 0; i < N * N; i++) R[i] = Rand();
    for (PetscInt i = 0; i < N; i++)
      for (PetscInt j = 0; j < N; j++) {
        PetscReal v = i == j ? N : 0;
        for (PetscInt l = 0; l < N; l++) v += R[i + N * l] * R[j + N * l];
        A[i + N * j] = v;
      }
  }
  /* U: per pair e_b - e_a on three DOFs each, as a contact element's columns */
  PetscCall(PetscArrayzero(U, N * M));
  for (PetscInt p = 0; p < K; p++)
    for (PetscInt l = 0; l < 3; l++) {
      U[(3 * p + l) + N * (3 * p + l)] += 1.0;
      U[(N - 1 - 3 * p - l) + N * (3 * p + l)] -= 1.0;
    }
  /* the pool: the correction's columns in shuffled slots, Z = A_ref^-1 U there, G = U' Z */
  for (PetscInt s = 0; s < LD / 3; s++) slot[s] = (5 * s + 3) % (LD / 3);
  for (PetscInt p = 0; p < K; p++)
    for (PetscInt l = 0; l < 3; l++) idx[3 * p + l] = 3 * slot[p] + l;
  PetscCall(PetscArrayzero(Zpool, N * LD));
  for (PetscInt p = 0; p < M; p++) PetscCall(PetscArraycpy(&Zpool[N * idx[p]], &U[N * p], N));
  PetscCall(DenseSolve(N, A, LD, Zpool, &singular));
  for (PetscInt i = 0; i < LD * LD; i++) Gpool[i] = 1e300; /* entries outside the correction must not be read */
  for (PetscInt p = 0; p < M; p++)
    for (PetscInt q = 0; q < M; q++) {
      PetscReal v = 0;
      for (PetscInt i = 0; i < N; i++) v += U[i + N * p] * Zpool[i + N * idx[q]];
      Gpool[idx[p] + LD * idx[q]] = v;
    }
  for (PetscInt i = 0; i < N; i++) b[i] = Rand();
  /* S: symmetric 3 x 3 blocks Q diag(lambda) Q' of ranks 0, 1, 2, 3 in turn, signs mixed, scales
     from a soft to a stiff penalty (the eigenvalues a step removes or adds) */
  PetscCall(PetscArrayzero(S, M * M));
  for (PetscInt p = 0; p < K; p++) {
    PetscReal Q[9], tau[3], work[9], lam[3];
    PetscBLASInt three = 3, lw = 9, info;
    const PetscInt rank = p % 4;
    for (PetscInt i = 0; i < 9; i++) Q[i] = Rand();
    PetscCallBLAS("LAPACKgeqrf", LAPACKgeqrf_(&three, &three, Q, &three, tau, work, &lw, &info));
    PetscCallBLAS("LAPACKorgqr", LAPACKorgqr_(&three, &three, &three, Q, &three, tau, work, &lw, &info));
    for (PetscInt l = 0; l < 3; l++) lam[l] = l < rank ? (l == 2 ? 1e-6 : l == 1 ? -0.4 : 1.0) * PetscPowReal(10.0, (PetscReal)(p % 3)) : 0;
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = 0; j < 3; j++) {
        PetscReal v = 0;
        for (PetscInt l = 0; l < 3; l++) v += Q[i + 3 * l] * lam[l] * Q[j + 3 * l];
        S[3 * p + i + M * (3 * p + j)] = v;
      }
    for (PetscInt i = 0; i < 3; i++) /* symmetric to the last bit, as a penalty block is */
      for (PetscInt j = 0; j < i; j++) S[3 * p + i + M * (3 * p + j)] = S[3 * p + j + M * (3 * p + i)];
  }
  PetscCall(Compare("blocks", A, U, S, Zpool, Gpool, idx, b, &nfail));
  /* a coupling between pairs 1 and 2 (as Gauss points make): the general path */
  S[3 + M * 6] = S[6 + M * 3] = 0.3;
  PetscCall(Compare("general", A, U, S, Zpool, Gpool, idx, b, &nfail));
  S[3 + M * 6] = S[6 + M * 3] = 0;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: %" PetscInt_FMT " check(s) failed\n", nfail ? "FAILED" : "ALL PASSED", nfail));
  PetscCall(PetscFinalize());
  return nfail ? 1 : 0;
}
