C     A FORTRAN 77 user subroutine's use of the utility subroutines, as
C     old user subroutines call them: fixed form, implicit interfaces.
C     It has a file of its own: gfortran checks the calls of one file
C     against each other, and an explicit interface (USE mbexpr) beside
C     an implicit call of the same routine draws "Shape mismatch in
C     argument 'vector'", though both are right.
      SUBROUTINE OLDSTYLE
      IMPLICIT NONE
      DOUBLE PRECISION VECTOR(3), VALUE
      LOGICAL ERRFLG
      INTEGER IORD
      DO 10 IORD = 0, 2
        CALL BISTOP(10.05D0, 0.7D0, -10.0D0, 10.0D0, 1.0D5, 2.2D0,
     &              100.0D0, 0.1D0, IORD, VECTOR, ERRFLG)
        WRITE (*, '(A, I1, A, 3ES22.13, A, L1)') 'BISTOP IORD=', IORD,
     &        ':', VECTOR, ' ERRFLG=', ERRFLG
   10 CONTINUE
      CALL IMPACT(0.95D0, -1.0D0, 1.0D0, 1.0D4, 1.5D0, 10.0D0, 0.1D0, 2,
     &            VECTOR, ERRFLG)
      WRITE (*, '(A, 3ES22.13, A, L1)') 'IMPACT IORD=2:', VECTOR,
     &      ' ERRFLG=', ERRFLG
      CALL STEP(0.25D0, 0.0D0, 0.0D0, 1.0D0, 10.0D0, 1, VALUE, ERRFLG)
      WRITE (*, '(A, ES22.13, A, L1)') 'STEP IORD=1:', VALUE,
     &      ' ERRFLG=', ERRFLG
      END
