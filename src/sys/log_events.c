/* Every -log_view event and stage of boltrom, registered once. */
#include <sys/resource.h>
#if defined(__GLIBC__)
  #include <malloc.h>
#endif
#include "boltrom.h"

BoltLog boltLog;

PetscErrorCode BoltLogRegister(void)
{
  static PetscBool registered = PETSC_FALSE;
  PetscClassId     classid;

  PetscFunctionBeginUser;
  if (registered) PetscFunctionReturn(0);
  registered = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("boltrom", &classid));
  PetscCall(PetscLogEventRegister("BoltMeshRead", classid, &boltLog.meshRead));
  PetscCall(PetscLogEventRegister("BoltMeshDistrib", classid, &boltLog.meshDistribute));
  PetscCall(PetscLogEventRegister("BoltAssembly", classid, &boltLog.assembly));
  PetscCall(PetscLogEventRegister("BoltContactSetUp", classid, &boltLog.contactSetUp));
  PetscCall(PetscLogEventRegister("BoltContactAsm", classid, &boltLog.contactAssembly));
  PetscCall(PetscLogEventRegister("BoltLoads", classid, &boltLog.loads));
  PetscCall(PetscLogEventRegister("BoltFactor", classid, &boltLog.factorization));
  PetscCall(PetscLogEventRegister("BoltStaticSolve", classid, &boltLog.staticSolve));
  PetscCall(PetscLogEventRegister("BoltModalSolve", classid, &boltLog.modalSolve));
  PetscCall(PetscLogEventRegister("BoltOutput", classid, &boltLog.output));
  PetscCall(PetscLogEventRegister("ContactStiffness", classid, &boltLog.contactStiffness));
  PetscCall(PetscLogEventRegister("Displacements", classid, &boltLog.displacements));
  PetscCall(PetscLogEventRegister("ContactForces", classid, &boltLog.contactForces));
  PetscCall(PetscLogEventRegister("ContactUpdate", classid, &boltLog.contactUpdate));
  PetscCall(PetscLogEventRegister("RomBasis", classid, &boltLog.basis));
  PetscCall(PetscLogEventRegister("RomProjection", classid, &boltLog.projection));
  PetscCall(PetscLogEventRegister("KrylovFactor", classid, &boltLog.krylovFactor));
  PetscCall(PetscLogEventRegister("KrylovSolve", classid, &boltLog.krylovSolve));
  PetscCall(PetscLogEventRegister("KrylovOrthog", classid, &boltLog.krylovOrth));
  PetscCall(PetscLogEventRegister("InterfaceReduce", classid, &boltLog.interfaceReduction));
  PetscCall(PetscLogStageRegister("Model set-up", &boltLog.stageSetUp));
  PetscCall(PetscLogStageRegister("Preload", &boltLog.stagePreload));
  PetscCall(PetscLogStageRegister("Transient", &boltLog.stageTransient));
  PetscCall(PetscLogStageRegister("Static solve", &boltLog.stageStatic));
  PetscCall(PetscLogStageRegister("Modal solve", &boltLog.stageModal));
  PetscCall(PetscLogStageRegister("Output", &boltLog.stageOutput));
  PetscFunctionReturn(0);
}

/* Resident memory of the largest rank, now and at its peak so far, in GB. Printed after the
   phases that hold FOM-sized factorisations: a big mesh shows where it stands before it runs
   out of memory, not after. */
PetscErrorCode BoltMemoryPrint(MPI_Comm comm, const char phase[])
{
  PetscLogDouble now, mine[2], most[2];
  struct rusage  ru;

  PetscFunctionBeginUser;
  PetscCall(PetscMemoryGetCurrentUsage(&now));
  PetscCheck(getrusage(RUSAGE_SELF, &ru) == 0, PETSC_COMM_SELF, PETSC_ERR_SYS, "getrusage failed");
  mine[0] = now / 1073741824.0;
  mine[1] = PetscMax(now, 1024.0 * (PetscLogDouble)ru.ru_maxrss) / 1073741824.0; /* Linux: kB */
  PetscCall(MPIU_Allreduce(mine, most, 2, MPI_DOUBLE, MPI_MAX, comm));
  PetscCall(PetscPrintf(comm, "Memory after %s: %.2f GB resident, peak %.2f GB (largest rank)\n", phase, most[0], most[1]));
  PetscFunctionReturn(0);
}

/* Hands the heap's free pages back to the system after a FOM-sized structure is destroyed. glibc
   keeps freed memory in its heap for reuse, and the next FOM-sized factorisation does not always
   fit in it: without this a run that has freed its factorisation still counts it as resident. */
PetscErrorCode BoltMemoryRelease(void)
{
  PetscFunctionBeginUser;
#if defined(__GLIBC__)
  (void)malloc_trim(0);
#endif
  PetscFunctionReturn(0);
}
