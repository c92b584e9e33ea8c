#include <math.h>
#include <stdint.h>
#include <string.h>
static uint64_t rs;
static inline uint64_t rnd(void){ rs += 0x9E3779B97F4A7C15ULL; uint64_t z=rs; z=(z^(z>>30))*0xBF58476D1CE4E5B9ULL; z=(z^(z>>27))*0x94D049BB133111EBULL; return z^(z>>31);}
static inline double rndu(void){ return (rnd()>>11)*(1.0/9007199254740992.0);}
/* E: point-indexed errors [N][K]; pi: pixel->point; S: pixel-indexed low-pass field (excl. self) */
void compute_S(int W,int K,const double*E,const int*pi,int M,const int*odx,const int*ody,const double*ow,double*S){
  int N=W*W; memset(S,0,sizeof(double)*N*K);
  for(int p=0;p<N;p++){int px=p%W,py=p/W;
    for(int m=0;m<M;m++){int q=((py+ody[m]+W)%W)*W+(px+odx[m]+W)%W; const double*e=E+(long)pi[q]*K; double*s=S+(long)p*K; double w=ow[m];
      for(int k=0;k<K;k++) s[k]+=w*e[k];}}
}
double energy(int W,int K,const double*E,const int*pi,const double*S){
  double tot=0; int N=W*W; for(int p=0;p<N;p++){const double*e=E+(long)pi[p]*K; const double*s=S+(long)p*K; for(int k=0;k<K;k++) tot+=e[k]*s[k];} return tot;}
/* R: window half-size; wl: (2R+1)^2 weight lookup (0 at centre) */
void optimize(int W,int K,const double*E,int*pi,double*S,int M,const int*odx,const int*ody,const double*ow,
              int R,const double*wl,long n_iter,double T0,double T1,int local_r,double p_local,uint64_t seed,long*stats,double*dE){
  rs=seed; int N=W*W; double d[4096]; long acc=0; double sumd=0;
  for(long it=0;it<n_iter;it++){
    double T = T0*pow(T1/T0,(double)it/(double)n_iter);
    int a=rnd()%N, b;
    if(rndu()<p_local){ int ax=a%W, ay=a/W; int L=2*local_r+1; int dx=(int)(rnd()%L)-local_r, dy=(int)(rnd()%L)-local_r; if(!dx&&!dy) continue; b=((ay+dy+W)%W)*W+(ax+dx+W)%W; }
    else { b=rnd()%N; if(b==a) continue; }
    const double*ea=E+(long)pi[a]*K,*eb=E+(long)pi[b]*K; const double*sa=S+(long)a*K,*sb=S+(long)b*K;
    double dot=0,dd=0;
    for(int k=0;k<K;k++){double t=eb[k]-ea[k]; d[k]=t; dot+=t*(sa[k]-sb[k]); dd+=t*t;}
    int ax=a%W,ay=a/W,bx=b%W,by=b/W; int dx=bx-ax,dy=by-ay; if(dx>W/2)dx-=W; if(dx<-W/2)dx+=W; if(dy>W/2)dy-=W; if(dy<-W/2)dy+=W;
    double wab=0; if(dx>=-R&&dx<=R&&dy>=-R&&dy<=R) wab=wl[(dy+R)*(2*R+1)+dx+R];
    double delta=2*dot-2*wab*dd;
    if(delta<0 || (T>0 && rndu()<exp(-delta/T))){
      for(int m=0;m<M;m++){ double w=ow[m];
        int q=((ay+ody[m]+W)%W)*W+(ax+odx[m]+W)%W; double*s=S+(long)q*K; for(int k=0;k<K;k++) s[k]+=w*d[k];
        q=((by+ody[m]+W)%W)*W+(bx+odx[m]+W)%W; s=S+(long)q*K; for(int k=0;k<K;k++) s[k]-=w*d[k]; }
      int t=pi[a]; pi[a]=pi[b]; pi[b]=t; acc++; sumd+=delta; }
  }
  stats[0]=acc; *dE=sumd;
}
