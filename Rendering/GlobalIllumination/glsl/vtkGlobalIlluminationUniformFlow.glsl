  // LinkGI: the triangle's normal, from derivatives that need uniform control flow.
  vec3 giTriangleNormalVC = cross(dFdx(vertexVC.xyz), dFdy(vertexVC.xyz));
