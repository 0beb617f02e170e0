/* Every -log_view event and stage of boltrom, registered once. */
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
