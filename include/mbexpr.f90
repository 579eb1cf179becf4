! mbexpr: explicit interfaces for the solver's utility subroutines, for
! FORTRAN user subroutines (`USE mbexpr`). Calling them without this module,
! as `CALL BISTOP(...)` with implicit interfaces, works too: the library
! exports the symbols gfortran emits (bistop_, impact_, step_).
!
! VECTOR(1..3): F, 0, 0 (IORD = 0); dF/dx, dF/dx', 0 (IORD = 1);
! d2F/dx2, d2F/dxdx', 0 (IORD = 2). ERRFLG is .TRUE. and VECTOR zero on a
! broken argument rule, an IORD other than 0, 1, 2, an input that is not
! finite, or an entry beyond the range of a double; otherwise every entry
! is a finite number. Keep implicit calls (old user subroutines) and calls
! through this module in separate files: gfortran checks the calls of one
! file against each other and takes VECTOR(3) and an implicit array
! argument for a "shape mismatch".
MODULE mbexpr
  IMPLICIT NONE
  INTERFACE
    SUBROUTINE BISTOP(X, XD, X1, X2, K, E, CMAX, D, IORD, VECTOR, ERRFLG)
      DOUBLE PRECISION, INTENT(IN) :: X, XD, X1, X2, K, E, CMAX, D
      INTEGER, INTENT(IN) :: IORD
      DOUBLE PRECISION, INTENT(OUT) :: VECTOR(3)
      LOGICAL, INTENT(OUT) :: ERRFLG
    END SUBROUTINE BISTOP

    SUBROUTINE IMPACT(X, XD, X1, K, E, CMAX, D, IORD, VECTOR, ERRFLG)
      DOUBLE PRECISION, INTENT(IN) :: X, XD, X1, K, E, CMAX, D
      INTEGER, INTENT(IN) :: IORD
      DOUBLE PRECISION, INTENT(OUT) :: VECTOR(3)
      LOGICAL, INTENT(OUT) :: ERRFLG
    END SUBROUTINE IMPACT

    SUBROUTINE STEP(X, X0, H0, X1, H1, IORD, VALUE, ERRFLG)
      DOUBLE PRECISION, INTENT(IN) :: X, X0, H0, X1, H1
      INTEGER, INTENT(IN) :: IORD
      DOUBLE PRECISION, INTENT(OUT) :: VALUE
      LOGICAL, INTENT(OUT) :: ERRFLG
    END SUBROUTINE STEP
  END INTERFACE
END MODULE mbexpr
