! A FORTRAN user subroutine's use of the utility subroutines, printed for a
! snapshot: first with implicit interfaces, as old user subroutines call
! them (OLDSTYLE, in the fixed-form old_style.f), then through the
! interface module.
PROGRAM USERSUB
  USE mbexpr
  IMPLICIT NONE
  DOUBLE PRECISION VECTOR(3)
  LOGICAL ERRFLG
  CALL OLDSTYLE
  CALL BISTOP(0.0D0, 0.0D0, 10.0D0, -10.0D0, 1.0D5, 2.2D0, 100.0D0, 0.1D0, 0, VECTOR, ERRFLG)
  WRITE (*, '(A, 3ES22.13, A, L1)') 'BISTOP X1>=X2:', VECTOR, ' ERRFLG=', ERRFLG
  CALL BISTOP(10.05D0, -100.0D0, -10.0D0, 10.0D0, 1.0D5, 2.2D0, 100.0D0, 0.1D0, 1, VECTOR, ERRFLG)
  WRITE (*, '(A, 3ES22.13, A, L1)') 'BISTOP CLAMPED:', VECTOR, ' ERRFLG=', ERRFLG
  ! A force beyond the range of a double: ERRFLG, never an infinity.
  CALL BISTOP(12.0D0, -1.0D306, -10.0D0, 10.0D0, 1.0D308, 3.0D0, 100.0D0, 0.1D0, 0, VECTOR, ERRFLG)
  WRITE (*, '(A, 3ES22.13, A, L1)') 'BISTOP OVERFLOW:', VECTOR, ' ERRFLG=', ERRFLG
END PROGRAM USERSUB
