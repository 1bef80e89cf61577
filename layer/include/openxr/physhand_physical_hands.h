#ifndef PHYSHAND_PHYSICAL_HANDS_H_
#define PHYSHAND_PHYSICAL_HANDS_H_ 1

/*
** XR_PHYSHAND_physical_hands: physical hands for OpenXR applications.
**
** Provided by the API layer XR_APILAYER_PHYSHAND_physical_hands. With the layer active,
** xrLocateHandJointsEXT returns a simulated *physical* hand driven toward the tracked
** (*ghost*) hand, colliding with the proxy colliders declared through this extension (and
** with the static colliders of the layer's config file). This extension lets an app
** declare and move those colliders, read them back, read the ghost hand and per-joint
** contact state, and choose the hand drive. An app that does not enable the extension
** still gets physical hands, colliding with the config file's colliders only.
**
** "physhand" is a private author tag, not a Khronos-registered one. Extension number
** 10042 was picked far from the registered ones, so by the OpenXR rule
** 1000000000 + (number - 1) * 1000 + offset its enumerant values are:
**
**   1010041000  XR_TYPE_PHYSICAL_COLLIDER_CREATE_INFO_PHYSHAND
**   1010041001  XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND
**   1010041002  XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND
**   1010041003  XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND
**   1010041004  XR_TYPE_HAND_JOINTS_PHYSICAL_STATE_PHYSHAND
**   1010041005  XR_TYPE_HAND_DRIVE_INFO_PHYSHAND
**   1010041006  XR_TYPE_HAND_COLLISION_SHAPES_PHYSHAND (spec version 2)
**   1010041007  XR_TYPE_PHYSICAL_CONTACT_REPORTING_INFO_PHYSHAND (spec version 3)
**   1010041008  XR_TYPE_PHYSICAL_CONTACT_EVENTS_GET_INFO_PHYSHAND (spec version 3)
**   1010041009  XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND (spec version 3)
**   1010041010  XR_TYPE_PHYSICAL_COLLIDER_IMPULSES_PHYSHAND (spec version 3)
**   1010041000  XR_OBJECT_TYPE_PHYSICAL_COLLIDER_PHYSHAND
**
** Frames and time. The layer simulates in the session's STAGE reference space (LOCAL if
** the runtime has no STAGE space). Every pose passed in or out names an XrSpace and an
** XrTime; the layer converts with xrLocateSpace at that time. Velocities are expressed in
** the axes of the named space; the motion of that space itself is not added or removed.
** Locating hand joints or colliders at a time later than the simulation's advances the
** simulation to that time, once: locating again at the same or an earlier time returns
** the current state and never steps backwards.
**
** Results. Every function validates its input:
**   XR_ERROR_VALIDATION_FAILURE  NULL pointers, wrong `type`, enum values out of range,
**                                NaN or infinite numbers, sizes or mass out of range,
**                                counts that do not match.
**   XR_ERROR_POSE_INVALID        a quaternion that is not unit length, or a pose whose
**                                `space` cannot be located at `time`.
**   XR_ERROR_TIME_INVALID        `time` <= 0.
**   XR_ERROR_HANDLE_INVALID      a session or collider the layer does not know (destroyed,
**                                or from another session), or an XR_NULL_HANDLE space.
**   XR_ERROR_SIZE_INSUFFICIENT   an output array too small (two-call idiom).
**   XR_ERROR_RUNTIME_FAILURE     anything unexpected inside the layer (the app is never
**                                crashed), or a session the layer could not set up.
** Errors from the runtime (for example an invalid XrSpace) are returned unchanged.
** If the user turned the layer off in its config file, xrGetInstanceProcAddr answers
** XR_ERROR_FUNCTION_UNSUPPORTED for this extension's functions even when it is enabled.
**
** Thread safety: all functions may be called from any thread; the layer serialises calls
** per session.
*/

#include <openxr/openxr.h>

#ifdef __cplusplus
extern "C" {
#endif

#define XR_PHYSHAND_physical_hands 1
/* Version 2 adds XrHandCollisionShapesPHYSHAND; version 1's behaviour is unchanged. */
#define XR_PHYSHAND_physical_hands_SPEC_VERSION 4
#define XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME "XR_PHYSHAND_physical_hands"

XR_DEFINE_HANDLE(XrPhysicalColliderPHYSHAND)

#define XR_TYPE_PHYSICAL_COLLIDER_CREATE_INFO_PHYSHAND ((XrStructureType)1010041000)
#define XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND ((XrStructureType)1010041001)
#define XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND ((XrStructureType)1010041002)
#define XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND ((XrStructureType)1010041003)
#define XR_TYPE_HAND_JOINTS_PHYSICAL_STATE_PHYSHAND ((XrStructureType)1010041004)
#define XR_TYPE_HAND_DRIVE_INFO_PHYSHAND ((XrStructureType)1010041005)
#define XR_TYPE_HAND_COLLISION_SHAPES_PHYSHAND ((XrStructureType)1010041006)
#define XR_TYPE_PHYSICAL_CONTACT_REPORTING_INFO_PHYSHAND ((XrStructureType)1010041007)
#define XR_TYPE_PHYSICAL_CONTACT_EVENTS_GET_INFO_PHYSHAND ((XrStructureType)1010041008)
#define XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND ((XrStructureType)1010041009)
#define XR_TYPE_PHYSICAL_COLLIDER_IMPULSES_PHYSHAND ((XrStructureType)1010041010)
#define XR_OBJECT_TYPE_PHYSICAL_COLLIDER_PHYSHAND ((XrObjectType)1010041000)

/* Shapes, in the collider's local frame (the frame of its pose). Zero is no shape, so a
** zero-initialised create info is rejected rather than silently becoming a box. */
typedef enum XrPhysicalColliderShapePHYSHAND {
    XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND = 1,      /* halfExtents */
    XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND = 2,   /* radius */
    XR_PHYSICAL_COLLIDER_SHAPE_CAPSULE_PHYSHAND = 3,  /* radius, halfHeight along local +Y */
    XR_PHYSICAL_COLLIDER_SHAPE_CYLINDER_PHYSHAND = 4, /* radius, halfHeight along local +Y */
    XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND = 5,   /* convex hull of vertices */
    XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND = 6,     /* triangles; static only */
    XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND = 7,    /* planeNormal, planeOffset; static only */
    XR_PHYSICAL_COLLIDER_SHAPE_MAX_ENUM_PHYSHAND = 0x7FFFFFFF
} XrPhysicalColliderShapePHYSHAND;

typedef enum XrPhysicalColliderMotionPHYSHAND {
    /* Never moves (a teleport may still place it). */
    XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND = 1,
    /* Moved by the app with xrSetPhysicalColliderPosePHYSHAND; pushes dynamic colliders
    ** and hands, is not pushed back. */
    XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND = 2,
    /* Simulated by the layer: gravity, contacts with hands and other colliders. */
    XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND = 3,
    XR_PHYSICAL_COLLIDER_MOTION_MAX_ENUM_PHYSHAND = 0x7FFFFFFF
} XrPhysicalColliderMotionPHYSHAND;

/* Hand drives: how the physical hand is pulled toward the ghost hand. */
typedef enum XrHandDriveKindPHYSHAND {
    /* The layer's default drive (the best one the project's benchmark found). */
    XR_HAND_DRIVE_KIND_DEFAULT_PHYSHAND = 0,
    /* Mahdi et al.'s drive: an explicit spring-damper force on every joint sphere. */
    XR_HAND_DRIVE_KIND_PAPER_PHYSHAND = 1,
    /* The same law solved implicitly (stable proportional-derivative) on joint spheres. */
    XR_HAND_DRIVE_KIND_IMPLICIT_PHYSHAND = 2,
    /* Implicit drive of a palm box and one capsule per bone, orientation driven too, every
    ** bone kept joined to the one before it and to the palm. */
    XR_HAND_DRIVE_KIND_BONES_PHYSHAND = 3,
    /* Since spec version 4: the bones drive (the name it had while it alone was joined). */
    XR_HAND_DRIVE_KIND_JOINTED_PHYSHAND = 4,
    XR_HAND_DRIVE_KIND_MAX_ENUM_PHYSHAND = 0x7FFFFFFF
} XrHandDriveKindPHYSHAND;

/* The shapes a physical hand collides as (XrHandCollisionShapesPHYSHAND). */
typedef enum XrHandCollisionShapeKindPHYSHAND {
    XR_HAND_COLLISION_SHAPE_KIND_SPHERE_PHYSHAND = 0,
    XR_HAND_COLLISION_SHAPE_KIND_CAPSULE_PHYSHAND = 1,
    XR_HAND_COLLISION_SHAPE_KIND_BOX_PHYSHAND = 2,
    XR_HAND_COLLISION_SHAPE_KIND_MAX_ENUM_PHYSHAND = 0x7FFFFFFF
} XrHandCollisionShapeKindPHYSHAND;

typedef XrFlags64 XrPhysicalColliderFlagsPHYSHAND;
/* A joint of the left (right) hand touched the collider during the last simulation step. */
static const XrPhysicalColliderFlagsPHYSHAND XR_PHYSICAL_COLLIDER_TOUCHED_BY_LEFT_BIT_PHYSHAND =
    0x00000001;
static const XrPhysicalColliderFlagsPHYSHAND XR_PHYSICAL_COLLIDER_TOUCHED_BY_RIGHT_BIT_PHYSHAND =
    0x00000002;
/* A dynamic collider at rest that the layer stopped simulating until something wakes it. */
static const XrPhysicalColliderFlagsPHYSHAND XR_PHYSICAL_COLLIDER_ASLEEP_BIT_PHYSHAND = 0x00000004;

/* A proxy collider: the app's stand-in for one of its objects.
** Sizes are metres, from 1e-4 to 1e4 where the shape uses them (a capsule's halfHeight may
** be 0); fields a shape does not use are ignored. `pose` places the collider's local frame in
** `space` at `time`. */
typedef struct XrPhysicalColliderCreateInfoPHYSHAND {
    XrStructureType type; /* XR_TYPE_PHYSICAL_COLLIDER_CREATE_INFO_PHYSHAND */
    const void* XR_MAY_ALIAS next;
    XrPhysicalColliderShapePHYSHAND shape;
    XrPhysicalColliderMotionPHYSHAND motion;
    XrVector3f halfExtents; /* box */
    float radius;           /* sphere, capsule, cylinder */
    float halfHeight;       /* capsule, cylinder: half the length of the straight part */
    uint32_t vertexCount;   /* convex (>= 4), mesh (>= 3) */
    const XrVector3f* vertices;
    uint32_t indexCount; /* mesh: a positive multiple of 3, each index < vertexCount */
    const uint32_t* indices;
    XrVector3f planeNormal; /* plane: the points p with dot(planeNormal, p) = planeOffset */
    float planeOffset;      /* (normal need not be unit length, must not be zero) */
    float mass;             /* kg; dynamic: 1e-6 .. 1e6; ignored otherwise */
    float friction;         /* >= 0; combined with the hand's by multiplication */
    float restitution;      /* 0 .. 1 */
    XrSpace space;
    XrPosef pose;
    XrTime time;
} XrPhysicalColliderCreateInfoPHYSHAND;

/* Moves a collider. Without `teleport`: a kinematic collider's target, reached at the end
** of the next simulation step (the collider sweeps there, pushing what is in the way);
** velocities are ignored, and any other collider is XR_ERROR_VALIDATION_FAILURE. With
** `teleport`: any collider is placed at `pose` at once and woken; a dynamic one takes the
** given velocities (ignored for the others). */
typedef struct XrPhysicalColliderPoseInfoPHYSHAND {
    XrStructureType type; /* XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND */
    const void* XR_MAY_ALIAS next;
    XrSpace space;
    XrTime time;
    XrPosef pose;
    XrBool32 teleport;
    XrVector3f linearVelocity;  /* m/s */
    XrVector3f angularVelocity; /* rad/s */
} XrPhysicalColliderPoseInfoPHYSHAND;

typedef struct XrPhysicalCollidersLocateInfoPHYSHAND {
    XrStructureType type; /* XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND */
    const void* XR_MAY_ALIAS next;
    XrSpace baseSpace;
    XrTime time;
    uint32_t colliderCount;
    const XrPhysicalColliderPHYSHAND* colliders; /* all of this session */
} XrPhysicalCollidersLocateInfoPHYSHAND;

typedef struct XrPhysicalColliderLocationPHYSHAND {
    /* Valid and tracked bits as for xrLocateSpace of the layer's frame in baseSpace; 0 and
    ** an identity pose when baseSpace cannot be located. */
    XrSpaceLocationFlags locationFlags;
    XrPosef pose;
    XrVector3f linearVelocity;
    XrVector3f angularVelocity;
    XrPhysicalColliderFlagsPHYSHAND flags;
} XrPhysicalColliderLocationPHYSHAND;

typedef struct XrPhysicalColliderLocationsPHYSHAND {
    XrStructureType type; /* XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND */
    void* XR_MAY_ALIAS next;
    uint32_t locationCount; /* must equal colliderCount */
    XrPhysicalColliderLocationPHYSHAND* locations;
} XrPhysicalColliderLocationsPHYSHAND;

/* Since spec version 3. Chained to XrPhysicalColliderLocationsPHYSHAND::next: for each
** located collider, the impulse both hands gave it since the app last read this collider's
** impulse (the first read starts the count and gives 0), and its moment about the
** collider's centre of mass, in baseSpace's axes. Each physics frame's impulse is read
** once, however often the app locates: apply what you read. Static and kinematic colliders
** get theirs too, though the layer does not move them, so that an app can keep an object
** in its own engine (the coupling recipe below). impulseCount must equal locationCount.
** While baseSpace cannot be located the impulses read 0 and are kept for a later read. */
/* Coupling recipe: an object the app keeps in its own physics engine.
**   1. Declare it to the layer as a KINEMATIC collider of the same shape.
**   2. Each frame, step the app's engine, then xrSetPhysicalColliderPosePHYSHAND the object
**      to where that engine has it, timed at the frame's display time (not teleported).
**   3. Locate hands and colliders at that time with XrPhysicalColliderImpulsesPHYSHAND
**      chained, and apply each object's impulses to it in the app's engine (linear at its
**      centre of mass, angular as a torque impulse); they act from its next step.
** The hands then push the object as the app's engine lets it move, and the layer's hands
** are stopped by it where the app's engine has it. Measured with the sample scenes (default
** drive; physhand-scene and physhand-sample give the same):
**   - Pushing works. app_push: the flat of the hand pushes a 0.2 kg cube 15 cm across a
**     table into its region; it ends 6 mm from where the same cube simulated by the layer
**     ends.
**   - Tipping works. A 16 cm post pushed near its top falls over, as the layer's own does
**     (tests/physics/scenes_test.cpp).
**   - Lifting does not. app_lift: as a pinch closes, the impulses, which are those that stop
**     the fingers against an object that cannot move, kick the 80 g cube out of the hand (at
**     up to 5.6 m/s, back onto the table); nothing is held. A grip needs the object in the
**     hands' own simulation: declare it DYNAMIC there (and teleport it to the app's pose when
**     the app moves it). */
typedef struct XrPhysicalColliderImpulsePHYSHAND {
    XrVector3f linearImpulse;  /* N*s */
    XrVector3f angularImpulse; /* N*m*s */
} XrPhysicalColliderImpulsePHYSHAND;

typedef struct XrPhysicalColliderImpulsesPHYSHAND {
    XrStructureType type; /* XR_TYPE_PHYSICAL_COLLIDER_IMPULSES_PHYSHAND */
    void* XR_MAY_ALIAS next;
    uint32_t impulseCount;
    XrPhysicalColliderImpulsePHYSHAND* impulses;
} XrPhysicalColliderImpulsesPHYSHAND;

/* Chained to XrHandJointLocationsEXT::next. Each array has jointCount (= 26) elements and
** may be NULL when the app does not want it. */
typedef struct XrHandJointsPhysicalStatePHYSHAND {
    XrStructureType type; /* XR_TYPE_HAND_JOINTS_PHYSICAL_STATE_PHYSHAND */
    void* XR_MAY_ALIAS next;
    uint32_t jointCount;
    /* The tracked hand as the runtime reported it, in baseSpace; meaningful only when
    ** ghostIsActive. */
    XrPosef* ghostPoses;
    /* The joint's physical body touched a collider during the last simulation step. */
    XrBool32* inContact;
    /* Magnitude of the drive (spring) force on the joint's body, newtons. */
    float* springForce;
    /* The runtime reported the hand active. The physical hand may stay active a short
    ** while after the ghost is lost, so that a brief dropout does not drop a held object. */
    XrBool32 ghostIsActive;
    /* XR_FALSE: no collider was near the hand, so it was not simulated and the joint
    ** locations are exactly the runtime's. */
    XrBool32 isSimulated;
} XrHandJointsPhysicalStatePHYSHAND;

/* One body of the physical hand. `pose` is its centre in baseSpace; a capsule's axis is
** the pose's Z axis. `size`: a sphere's radius in x; a capsule's radius in x and half the
** distance between the centres of its two ends in z; a box's half extents. */
typedef struct XrHandCollisionShapePHYSHAND {
    XrHandCollisionShapeKindPHYSHAND kind;
    XrPosef pose;
    XrVector3f size;
    /* The body touched a collider during the last simulation step. */
    XrBool32 inContact;
} XrHandCollisionShapePHYSHAND;

/* Since spec version 2. Chained to XrHandJointLocationsEXT::next: the bodies the physical
** hand collides as, placed as the returned joints are (drawn as they are, they show what
** touches: the default drive's palm is a box and its fingers one capsule per bone; the
** paper and implicit drives' hands are a sphere per joint). Two-call idiom:
** shapeCapacityInput 0 asks for shapeCountOutput only; a capacity under it fails with
** XR_ERROR_SIZE_INSUFFICIENT (shapeCountOutput set). A hand has at most
** XR_HAND_JOINT_COUNT_EXT shapes, and none when it is not active or its tracker is not
** one the layer simulates (another joint set, or a locate with anything chained to its
** info). A hand far from every collider is not simulated: its shapes are then where its
** bodies would be on the tracked hand. */
typedef struct XrHandCollisionShapesPHYSHAND {
    XrStructureType type; /* XR_TYPE_HAND_COLLISION_SHAPES_PHYSHAND */
    void* XR_MAY_ALIAS next;
    uint32_t shapeCapacityInput;
    uint32_t shapeCountOutput;
    XrHandCollisionShapePHYSHAND* shapes;
} XrHandCollisionShapesPHYSHAND;

/* Changes the hand drive of both hands of a session, from the next simulation step on.
** stiffness (N/m), damping (N*s/m) and forceLimit (N per body) must be >= 0, substeps
** (per 90 Hz frame) <= 64; 0 keeps the chosen drive's own value. */
typedef struct XrHandDriveInfoPHYSHAND {
    XrStructureType type; /* XR_TYPE_HAND_DRIVE_INFO_PHYSHAND */
    const void* XR_MAY_ALIAS next;
    XrHandDriveKindPHYSHAND drive;
    float stiffness;
    float damping;
    float forceLimit;
    uint32_t substeps;
} XrHandDriveInfoPHYSHAND;

/* Since spec version 3: contact events, for sound, haptics and apps that keep their own
** physics. A pair is one body of one hand (a finger bone, the palm, or a joint's sphere)
** and one collider, or (only when asked for: colliderContacts) two colliders; it begins in
** the first physics frame (1/90 s) in which they touch, persists while they do, and ends in
** the first frame in which they no longer do (also when the hand stops being simulated or a
** collider is destroyed). */
typedef enum XrPhysicalContactEventKindPHYSHAND {
    XR_PHYSICAL_CONTACT_EVENT_KIND_BEGIN_PHYSHAND = 1,
    XR_PHYSICAL_CONTACT_EVENT_KIND_PERSIST_PHYSHAND = 2,
    XR_PHYSICAL_CONTACT_EVENT_KIND_END_PHYSHAND = 3,
    XR_PHYSICAL_CONTACT_EVENT_KIND_MAX_ENUM_PHYSHAND = 0x7FFFFFFF
} XrPhysicalContactEventKindPHYSHAND;

/* Turns recording on for a session (nothing is recorded before this call or the first
** xrGetPhysicalContactEventsPHYSHAND, which turns it on with the defaults), or changes it.
** eventCapacity: how many events are kept until the app reads them, 1 to 65536; 0 means
** 1024. Events that come to a full buffer are dropped and counted (lostEventCount); a
** smaller capacity than the events waiting drops the newest. persistEvents: also one
** PERSIST event per pair and physics frame (90 a second for each touching body: ask for
** them only to sum impulses). colliderContacts: also contacts between two colliders (a
** stack of ten boxes resting is some thirty pairs; not asked for, nothing is spent on
** them). */
typedef struct XrPhysicalContactReportingInfoPHYSHAND {
    XrStructureType type; /* XR_TYPE_PHYSICAL_CONTACT_REPORTING_INFO_PHYSHAND */
    const void* XR_MAY_ALIAS next;
    XrBool32 persistEvents;
    uint32_t eventCapacity;
    XrBool32 colliderContacts;
} XrPhysicalContactReportingInfoPHYSHAND;

typedef struct XrPhysicalContactEventPHYSHAND {
    XrPhysicalContactEventKindPHYSHAND kind;
    /* 0 for a contact between two colliders (otherCollider set; joint then means nothing). */
    XrHandEXT hand;
    /* The first joint the touching body carries: a finger bone's base joint (the index
    ** finger's proximal bone is XR_HAND_JOINT_INDEX_PROXIMAL_EXT, its last bone, which
    ** carries the tip, XR_HAND_JOINT_INDEX_DISTAL_EXT), the palm for the default drive's
    ** palm box, the joint itself for the sphere drives. */
    XrHandJointEXT joint;
    /* XR_NULL_HANDLE for a collider of the layer's config file, or one destroyed since. */
    XrPhysicalColliderPHYSHAND collider;
    /* A contact between colliders: the one that touched `collider` (XR_NULL_HANDLE also as
    ** for `collider`); XR_NULL_HANDLE for a hand's contact. */
    XrPhysicalColliderPHYSHAND otherCollider;
    XrTime time; /* the end of the physics frame */
    /* In baseSpace: where they touched deepest in that frame (an END: where they last
    ** touched), on `collider`'s surface, and the surface normal there, from `collider`
    ** toward the hand (or the other collider). */
    XrVector3f point;
    XrVector3f normal;
    /* The normal impulse between them over the frame, N*s (0 for END). */
    float impulse;
    /* The impulse the collider took from this body over the frame, normal and friction,
    ** N*s, in baseSpace's axes (0 for END): summed over a collider's BEGIN and PERSIST
    ** events, what the hands did to its momentum. Also for static and kinematic
    ** colliders, which the layer does not move: an app simulating the object itself
    ** applies it in its own engine. */
    XrVector3f linearImpulse;
    /* BEGIN: how fast they approached along the normal when they met, m/s. 0 otherwise. */
    float approachSpeed;
} XrPhysicalContactEventPHYSHAND;

/* Positions and directions are given in baseSpace located at `time`; a baseSpace that
** cannot be located then fails with XR_ERROR_POSE_INVALID and reads nothing. */
typedef struct XrPhysicalContactEventsGetInfoPHYSHAND {
    XrStructureType type; /* XR_TYPE_PHYSICAL_CONTACT_EVENTS_GET_INFO_PHYSHAND */
    const void* XR_MAY_ALIAS next;
    XrSpace baseSpace;
    XrTime time;
} XrPhysicalContactEventsGetInfoPHYSHAND;

/* The events since the app last read them, oldest first, from the physics frames simulated
** so far (locating hand joints or colliders advances the simulation; this call does not).
** Two-call idiom: eventCapacityInput 0 asks for eventCountOutput and reads nothing; a
** capacity under the count fails with XR_ERROR_SIZE_INSUFFICIENT (eventCountOutput set);
** otherwise the events are copied and removed from the buffer. lostEventCount: events
** dropped because the buffer was full since the last successful read (set by every call;
** reset by a read). */
typedef struct XrPhysicalContactEventsPHYSHAND {
    XrStructureType type; /* XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND */
    void* XR_MAY_ALIAS next;
    uint32_t eventCapacityInput;
    uint32_t eventCountOutput;
    XrPhysicalContactEventPHYSHAND* events;
    uint32_t lostEventCount;
} XrPhysicalContactEventsPHYSHAND;

typedef XrResult(XRAPI_PTR* PFN_xrCreatePhysicalColliderPHYSHAND)(
    XrSession session, const XrPhysicalColliderCreateInfoPHYSHAND* createInfo,
    XrPhysicalColliderPHYSHAND* collider);
typedef XrResult(XRAPI_PTR* PFN_xrDestroyPhysicalColliderPHYSHAND)(
    XrPhysicalColliderPHYSHAND collider);
typedef XrResult(XRAPI_PTR* PFN_xrSetPhysicalColliderPosePHYSHAND)(
    XrPhysicalColliderPHYSHAND collider, const XrPhysicalColliderPoseInfoPHYSHAND* poseInfo);
typedef XrResult(XRAPI_PTR* PFN_xrLocatePhysicalCollidersPHYSHAND)(
    XrSession session, const XrPhysicalCollidersLocateInfoPHYSHAND* locateInfo,
    XrPhysicalColliderLocationsPHYSHAND* locations);
typedef XrResult(XRAPI_PTR* PFN_xrSetHandDrivePHYSHAND)(XrSession session,
                                                        const XrHandDriveInfoPHYSHAND* driveInfo);
typedef XrResult(XRAPI_PTR* PFN_xrSetPhysicalContactReportingPHYSHAND)(
    XrSession session, const XrPhysicalContactReportingInfoPHYSHAND* reportingInfo);
typedef XrResult(XRAPI_PTR* PFN_xrGetPhysicalContactEventsPHYSHAND)(
    XrSession session, const XrPhysicalContactEventsGetInfoPHYSHAND* getInfo,
    XrPhysicalContactEventsPHYSHAND* events);

#ifndef XR_NO_PROTOTYPES
#ifdef XR_EXTENSION_PROTOTYPES
XRAPI_ATTR XrResult XRAPI_CALL xrCreatePhysicalColliderPHYSHAND(
    XrSession session, const XrPhysicalColliderCreateInfoPHYSHAND* createInfo,
    XrPhysicalColliderPHYSHAND* collider);
XRAPI_ATTR XrResult XRAPI_CALL
xrDestroyPhysicalColliderPHYSHAND(XrPhysicalColliderPHYSHAND collider);
XRAPI_ATTR XrResult XRAPI_CALL xrSetPhysicalColliderPosePHYSHAND(
    XrPhysicalColliderPHYSHAND collider, const XrPhysicalColliderPoseInfoPHYSHAND* poseInfo);
XRAPI_ATTR XrResult XRAPI_CALL xrLocatePhysicalCollidersPHYSHAND(
    XrSession session, const XrPhysicalCollidersLocateInfoPHYSHAND* locateInfo,
    XrPhysicalColliderLocationsPHYSHAND* locations);
XRAPI_ATTR XrResult XRAPI_CALL xrSetHandDrivePHYSHAND(XrSession session,
                                                      const XrHandDriveInfoPHYSHAND* driveInfo);
XRAPI_ATTR XrResult XRAPI_CALL xrSetPhysicalContactReportingPHYSHAND(
    XrSession session, const XrPhysicalContactReportingInfoPHYSHAND* reportingInfo);
XRAPI_ATTR XrResult XRAPI_CALL xrGetPhysicalContactEventsPHYSHAND(
    XrSession session, const XrPhysicalContactEventsGetInfoPHYSHAND* getInfo,
    XrPhysicalContactEventsPHYSHAND* events);
#endif /* XR_EXTENSION_PROTOTYPES */
#endif /* !XR_NO_PROTOTYPES */

#ifdef __cplusplus
}
#endif

#endif /* PHYSHAND_PHYSICAL_HANDS_H_ */
