; narrow_ints.ll: Oclgrind 21.10 does not wrap integers narrower than their storage
; (LLVM's i2, i31, ...): an add or trunc keeps the bits above the type's width. Its own
; compiler (clang 14) emits such types from range facts: a switch on k % 4 becomes a
; switch on i2 (rsl_mget, so the hoisted matrix of Shading.HoistedUniformWorkEqualsPer-
; PointWork comes back with wrong rows), and `lane == 1 || lane == 2` becomes
; `(i31)lane - 1 <u 2` (filterstep's neighbour record, Derivatives.FilterstepIsAntialiased).
; out[0] is the input; the kernel writes out[1] = ((i31)out[0] - 1 <u 2) and
; out[2] = ((i2)out[0] == 1). Right answers for out[0] = 5: 0 and 1; for 1: 1 and 1.
target datalayout = "e-i64:64-v16:16-v24:32-v32:32-v48:64-v96:128-v192:256-v256:256-v512:512-v1024:1024"
target triple = "spir64-unknown-unknown"
define spir_kernel void @narrow_ints(i32 addrspace(1)* %out) !kernel_arg_addr_space !1 !kernel_arg_access_qual !2 !kernel_arg_type !3 !kernel_arg_base_type !3 !kernel_arg_type_qual !4 !kernel_arg_name !5 {
entry:
  %v = load i32, i32 addrspace(1)* %out
  %t = trunc i32 %v to i31
  %o = add i31 %t, -1
  %c = icmp ult i31 %o, 2
  %r = zext i1 %c to i32
  %p1 = getelementptr i32, i32 addrspace(1)* %out, i64 1
  store i32 %r, i32 addrspace(1)* %p1
  %t2 = trunc i32 %v to i2
  %c2 = icmp eq i2 %t2, 1
  %r2 = zext i1 %c2 to i32
  %p2 = getelementptr i32, i32 addrspace(1)* %out, i64 2
  store i32 %r2, i32 addrspace(1)* %p2
  ret void
}
!1 = !{i32 1}
!2 = !{!"none"}
!3 = !{!"int*"}
!4 = !{!""}
!5 = !{!"out"}
